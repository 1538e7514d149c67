"""The simpartner Python module against a real simpartner-sim on the bus
(udpm, ttl=0, a port of its own) and a real private MariaDB written by a real
simpartner-logger. Run by ctest with the interpreter the module was built
for and PYTHONPATH at the build's module."""
import functools
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np

import simpartner

BINARY_DIR = os.environ["SP_BINARY_DIR"]
SOURCE_DIR = os.environ["SP_SOURCE_DIR"]


@functools.lru_cache(maxsize=None)
def unique_url(offset):
    """This test's bus number `offset`, from tests/support/bus_url.h (a port
    no other process holds), the same for every call with that offset."""
    return subprocess.check_output(
        [BINARY_DIR + "/tests/sp_test_bus_url", str(offset)], text=True,
        env=child_env()).strip()


def child_env():
    # The ASan runtime is preloaded for python3 only (a sanitized tree):
    # mariadbd must not get it, and the sanitized programs link their own
    # (clang's, linked in, refuses a second one: "incompatible ASan
    # runtimes").
    env = dict(os.environ)
    env.pop("LD_PRELOAD", None)
    env.pop("ASAN_OPTIONS", None)
    return env


def read(path):
    with open(path) as f:
        return f.read()


def start_sim(url, log, extra=()):
    return subprocess.Popen(
        [BINARY_DIR + "/sim_core/simpartner-sim", "--params", "/dev/null",
         "--environment=" + SOURCE_DIR + "/models/worlds/flat_ground.xml",
         "--lcm-url", url] + list(extra),
        stdout=log, stderr=subprocess.STDOUT, env=child_env())


def stop(process):
    if process.poll() is None:
        process.terminate()
        try:
            process.wait(20)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


class InterpreterTest(unittest.TestCase):
    """The module refuses, at import, an interpreter it cannot work in and
    names the one it was built for (a pyenv python3 first on PATH of the
    same version loaded it and failed at the first array: no numpy)."""

    def test_ctest_runs_the_interpreter_the_module_was_built_for(self):
        self.assertEqual(os.path.realpath(simpartner.BUILT_FOR_PYTHON),
                         os.path.realpath(sys.executable))

    def test_an_interpreter_without_numpy_is_refused_by_name(self):
        # -S: no site packages, so Debian's numpy is out of reach as it is
        # for another interpreter; PYTHONPATH still finds the module.
        done = subprocess.run([sys.executable, "-S", "-c", "import simpartner"],
                              env=dict(os.environ), capture_output=True, text=True,
                              timeout=60)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("ImportError: simpartner was built for " + simpartner.BUILT_FOR_PYTHON +
                      " (Python ", done.stderr)
        self.assertIn("cannot import numpy, which the module's arrays need "
                      "(No module named 'numpy'). Run it with " + simpartner.BUILT_FOR_PYTHON,
                      done.stderr)


class BusTest(unittest.TestCase):
    """Connect, model, state, commands and run control on a running gen3."""

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="sp_py_")
        cls.url = unique_url(1)
        cls.log = open(os.path.join(cls.dir, "sim.log"), "w")
        cls.sim_process = start_sim(cls.url, cls.log)
        cls.sim = simpartner.Sim(cls.url, timeout=30.0)

    @classmethod
    def tearDownClass(cls):
        del cls.sim
        stop(cls.sim_process)
        cls.log.close()
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_no_sim_is_a_typed_error(self):
        with self.assertRaises(simpartner.NoSim) as caught:
            simpartner.Sim(unique_url(2), timeout=0.5)
        self.assertIsInstance(caught.exception, simpartner.ClientError)
        self.assertIn(unique_url(2).split("?")[0], str(caught.exception))

    def test_model_names_and_kinds(self):
        model = self.sim.model()
        self.assertEqual(model["world"], "FlatGround")
        self.assertIn("Wheel1", model["bodies"])
        self.assertIn("Axle1", model["joints"])
        kinds = {t["name"]: t["kind"] for t in model["targets"]}
        self.assertEqual(kinds["Axle1Motor"], "actuator")
        self.assertAlmostEqual(model["step_size"], 0.001)

    def test_state_arrays_have_the_model_shape(self):
        state = self.sim.wait_until(0.1, timeout=30)
        model = self.sim.model()
        self.assertEqual(state["position"].shape, (len(model["bodies"]), 3))
        self.assertEqual(state["orientation"].shape, (len(model["bodies"]), 4))
        self.assertEqual(state["joint_angle"].shape, (len(model["joints"]), 3))
        # Unit quaternions; the robot stands above the ground (y up).
        self.assertTrue(np.allclose(np.linalg.norm(state["orientation"], axis=1), 1.0, atol=1e-6))
        wheel = model["bodies"].index("Wheel1")
        self.assertGreater(state["position"][wheel, 1], 0.0)
        # Rigid ground: no wheel on soil, but the arrays are there, empty.
        soil = state["wheel_soil"]
        self.assertEqual(soil["body"].shape, (0,))
        self.assertEqual(soil["normal_force"].shape, (0, 3))
        self.assertEqual(set(soil), {"body", "sinkage", "slip", "normal_force", "shear_force",
                                     "thrust", "drawbar_pull", "load", "axle_torque", "stuck"})

    def test_field_sensor_readings_as_numpy(self):
        imu = self.sim.wait_reading("Imu", timeout=10.0)
        self.assertEqual(imu["kind"], "imu")
        self.assertEqual(imu["columns"],
                         ["ax", "ay", "az", "wx", "wy", "wz", "qw", "qx", "qy", "qz"])
        self.assertEqual(imu["values"].shape, (10,))
        self.assertEqual(imu["values"].dtype, np.float64)
        # Standing on flat ground (y up): the specific force is +g up.
        self.assertAlmostEqual(imu["values"][1], 9.81, delta=1.0)
        # gen3's lidar: 4 layers of 221 rays, as layers x rays.
        lidar = self.sim.wait_reading("Lidar", timeout=10.0)
        self.assertEqual(lidar["values"].shape, (4, 221))
        self.assertEqual(lidar["columns"][0], "range_0")
        self.assertEqual(len(lidar["columns"]), 221)
        self.assertTrue(np.all(lidar["values"] > 0))
        encoder = self.sim.wait_reading("Encoder1", timeout=10.0)
        self.assertEqual(encoder["columns"], ["count", "count_rate"])
        self.assertEqual(encoder["values"][0], math.floor(encoder["values"][0]))  # counts
        # A camera has no readings, and a sensor no images.
        with self.assertRaises(simpartner.UnknownTarget):
            self.sim.image("Imu")

    def test_wheel_turns_at_the_rate_it_is_given(self):
        model = self.sim.model()
        axle = model["joints"].index("Axle1")
        self.sim.set_velocity("Axle1Motor", [2.0])
        start = self.sim.state()["time"]
        state = self.sim.wait_until(start + 1.0, timeout=30)
        self.assertAlmostEqual(abs(state["joint_rate"][axle, 0]), 2.0, delta=0.05)
        # At speed, 2 s more turn it 4 rad, past the +-pi where joint_angle wraps.
        later = self.sim.wait_until(state["time"] + 2.0, timeout=30)
        turned = later["joint_continuous_angle"][axle, 0] - state["joint_continuous_angle"][axle, 0]
        self.assertAlmostEqual(abs(turned), 2.0 * (later["time"] - state["time"]), delta=0.15)
        self.assertLessEqual(abs(later["joint_angle"][axle, 0]), math.pi)
        self.sim.set_velocity("Axle1Motor", [0.0])

    def test_errors_are_typed(self):
        with self.assertRaises(simpartner.UnknownTarget) as caught:
            self.sim.set_velocity("Axle1Motr", [1.0])
        self.assertIn("Axle1Motor", str(caught.exception))
        with self.assertRaises(simpartner.BadValues):
            self.sim.set_velocity("Axle1Motor", [float("nan")])
        with self.assertRaises(simpartner.Timeout):
            self.sim.wait_until(1e9, timeout=0.3)

    def test_pause_step_resume(self):
        self.sim.pause()
        time.sleep(0.5)
        before = self.sim.state()["step"]
        time.sleep(0.5)
        self.assertEqual(self.sim.state()["step"], before)
        self.sim.step(20)
        deadline = time.time() + 10
        while self.sim.state()["step"] < before + 20 and time.time() < deadline:
            time.sleep(0.05)
        self.assertEqual(self.sim.state()["step"], before + 20)
        self.sim.resume()
        self.sim.wait_until(self.sim.state()["time"] + 0.2, timeout=30)

    def test_hold_and_reset(self):
        self.assertGreaterEqual(self.sim.hold("Hip1Motor"), 0)
        old = self.sim.model()["simulation_id"]
        self.sim.reset(timeout=30)
        self.assertNotEqual(self.sim.model()["simulation_id"], old)


class ImageTest(unittest.TestCase):
    """Camera images as NumPy arrays: gen3's HeadCamera (640 x 480, depth in
    millimetres), its images published by a stand-in for simpartner-camera
    (tests/support/publish_image_main.cpp) with a pattern known here."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="sp_pyimg_")
        url = unique_url(5)
        self.log = open(os.path.join(self.dir, "sim.log"), "w")
        self.sim_process = start_sim(url, self.log)
        self.camera = subprocess.Popen(
            [BINARY_DIR + "/tests/sp_test_publish_image", url, "HeadCamera", "60"],
            stdout=self.log, stderr=subprocess.STDOUT, env=child_env())
        self.sim = simpartner.Sim(url, timeout=30.0)

    def tearDown(self):
        del self.sim
        stop(self.camera)
        stop(self.sim_process)
        self.log.close()
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_colour_and_depth_images(self):
        self.assertIsNone(self.sim.image("HeadCamera"))  # not received before asked for
        colour = self.sim.wait_image("HeadCamera", timeout=20.0)
        self.assertEqual((colour["width"], colour["height"], colour["format"]), (640, 480, "rgb8"))
        pixels = colour["pixels"]
        self.assertEqual(pixels.shape, (480, 640, 3))
        self.assertEqual(pixels.dtype, np.uint8)
        # Row 5, column 300: red = 300 % 256, green = 5, blue = 7.
        self.assertEqual(list(pixels[5, 300]), [44, 5, 7])
        self.assertEqual(list(pixels[479, 0]), [0, 479 % 256, 7])
        self.assertAlmostEqual(colour["time"], colour["step"] * 0.001, places=9)
        self.assertIsNotNone(self.sim.image("HeadCamera"))
        depth = self.sim.wait_image("HeadCamera", after_step=colour["step"] - 1, timeout=20.0,
                                    depth=True)
        self.assertEqual(depth["format"], "depth-u16")
        self.assertEqual(depth["pixels"].shape, (480, 640))
        self.assertEqual(depth["pixels"].dtype, np.uint16)
        self.assertEqual(depth["pixels"][0, 10], 1010)  # millimetres
        self.assertEqual(depth["pixels"][479, 639], 1639)
        later = self.sim.wait_image("HeadCamera", after_step=depth["step"], timeout=20.0)
        self.assertGreater(later["step"], depth["step"])


class ExampleTest(unittest.TestCase):
    """examples/drive_and_plot.py drives a real sim and writes its plot (Agg)."""

    def test_drive_and_plot(self):
        work = tempfile.mkdtemp(prefix="sp_pyex_")
        url = unique_url(4)
        log = open(os.path.join(work, "sim.log"), "w")
        sim_process = start_sim(url, log)
        try:
            env = dict(os.environ)  # the module's environment (and ASan preload)
            env.pop("DISPLAY", None)
            out = os.path.join(work, "run.png")
            done = subprocess.run(
                [sys.executable, SOURCE_DIR + "/examples/drive_and_plot.py", "--lcm-url", url, "--seconds", "3",
                 "--out", out],
                env=env, capture_output=True, text=True, timeout=240)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertIn("plot in " + out, done.stdout)
            with open(out, "rb") as png:
                self.assertEqual(png.read(8), b"\x89PNG\r\n\x1a\n")
            self.assertGreater(os.path.getsize(out), 20000)
            if os.environ.get("SP_PLOT_DIR"):
                shutil.copy(out, os.environ["SP_PLOT_DIR"])
        finally:
            stop(sim_process)
            log.close()
            shutil.rmtree(work, ignore_errors=True)


def start_paused_sim(url, log, world, speed):
    return subprocess.Popen(
        [BINARY_DIR + "/sim_core/simpartner-sim", "--params", "/dev/null",
         "--environment=" + SOURCE_DIR + "/models/worlds/" + world, "--lcm-url", url,
         "--startPaused=1", "--speed=%g" % speed],
        stdout=log, stderr=subprocess.STDOUT, env=child_env())


class LockStepTest(unittest.TestCase):
    """sim.lockstep: a closed loop in Python repeats; commands land in the next step."""

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="sp_pyls_")
        self.processes = []

    def tearDown(self):
        for process, log in self.processes:
            stop(process)
            log.close()
        shutil.rmtree(self.dir, ignore_errors=True)

    def sim(self, offset, speed, world="gen1_flat.xml"):
        url = unique_url(offset)
        log = open(os.path.join(self.dir, "sim%d.log" % offset), "w")
        self.processes.append((start_paused_sim(url, log, world, speed), log))
        return simpartner.Sim(url, timeout=30.0, program="lockstep_test")

    def closed_loop(self, sim):
        """Steers gen1's Turner joint from its heading for 1500 steps; every
        tick's positions and joint angles."""
        front = sim.model()["bodies"].index("FrontChassis")
        seen = []
        for state in sim.lockstep(period=5, steps=300):
            seen.append(np.concatenate([state["position"].ravel(), state["joint_angle"].ravel()]))
            q = state["orientation"][front]
            heading = math.atan2(-2 * (q[1] * q[3] - q[0] * q[2]), 1 - 2 * (q[2] ** 2 + q[3] ** 2))
            for w in range(1, 5):
                sim.set_velocity("Axle%dMotor" % w, [2.0 + state["time"]])
            sim.set_angle("TurnerMotor", [max(-0.3, min(0.3, 0.5 - heading))], 100, 100, 0)
        return np.array(seen)

    def test_a_closed_loop_repeats_bit_for_bit_at_any_speed(self):
        fast = self.closed_loop(self.sim(10, 0))
        real_time = self.closed_loop(self.sim(11, 2))
        self.assertEqual(fast.shape, real_time.shape)
        self.assertEqual(fast.shape[0], 300)
        self.assertTrue(np.array_equal(fast, real_time))  # bit for bit, not approximately
        self.assertGreater(np.ptp(fast[:, 0]), 0.5)  # it drove

    def test_commands_apply_in_the_step_after_the_tick(self):
        sim = self.sim(12, 0)
        axle = sim.model()["joints"].index("Axle1")
        loop = sim.lockstep(period=1)
        ticks = []
        for state in loop:
            ticks.append(state)
            if len(ticks) == 3:
                self.assertEqual(sim.set_velocity("Axle1Motor", [3.0]), state["step"])
            if len(ticks) == 5:
                break
        loop.close()
        # Before the tick the command was given at, the wheel held still;
        # in the step after it, its motor turns it.
        self.assertAlmostEqual(ticks[2]["joint_rate"][axle, 0], 0.0, delta=1e-3)
        self.assertGreater(abs(ticks[3]["joint_rate"][axle, 0]), 1.0)

    def test_a_refused_command_raises_at_the_next_tick_and_the_loop_leaves(self):
        sim = self.sim(13, 0)
        with self.assertRaises(simpartner.Refused) as caught:
            for state in sim.lockstep(period=2, name="refused"):
                sim.set_angle("TurnerMotor", [3.0])  # beyond the Turner joint's range
        self.assertIn("TurnerMotor", str(caught.exception))
        # The loop left lock-step: the sim runs on, and the name is free again.
        step = sim.state()["step"]
        time.sleep(0.3)
        self.assertGreater(sim.state()["step"], step)
        for state in sim.lockstep(period=2, steps=3, name="refused"):
            pass

    def test_scanner_readings_as_numpy(self):
        sim = self.sim(14, 0, world="scanner_wall.xml")
        for state in sim.lockstep(period=10, steps=5):
            if state["step"] == 0:
                sim.command("Scanner", "1000", action="params")
        scan = sim.reading("Scanner")
        self.assertIsInstance(scan["values"], np.ndarray)
        self.assertEqual(scan["values"].shape, (11,))
        # The middle ray: the wall 5.335 m ahead of the scanner.
        self.assertAlmostEqual(scan["values"][5], 5.335, delta=0.01)
        with self.assertRaises(simpartner.UnknownTarget):
            sim.reading("Scaner")


class ReadmeAndLockStepExampleTest(unittest.TestCase):
    """The README's first Python controller, as printed, and
    examples/lockstep_stop_at_wall.py, each against a real sim."""

    def run_python(self, url, script_args, world, extra=()):
        work = tempfile.mkdtemp(prefix="sp_pyrd_")
        log = open(os.path.join(work, "sim.log"), "w")
        sim_process = subprocess.Popen(
            [BINARY_DIR + "/sim_core/simpartner-sim", "--params", "/dev/null",
             "--environment=" + SOURCE_DIR + "/models/worlds/" + world, "--lcm-url", url]
            + list(extra), stdout=log, stderr=subprocess.STDOUT, env=child_env())
        try:
            return subprocess.run([sys.executable] + script_args, env=dict(os.environ),
                                  capture_output=True, text=True, timeout=240)
        finally:
            stop(sim_process)
            log.close()
            shutil.rmtree(work, ignore_errors=True)

    def test_the_readmes_python_controller(self):
        readme = read(SOURCE_DIR + "/README.md")
        start = readme.index("```python\n") + len("```python\n")
        code = readme[start:readme.index("```", start)]
        self.assertIn("simpartner.Sim()", code)
        url = unique_url(20)
        # On this test's bus instead of the default one.
        code = code.replace("simpartner.Sim()", "simpartner.Sim(%r, timeout=30.0)" % url)
        done = self.run_python(url, ["-c", code], "flat_ground.xml")
        self.assertEqual(done.returncode, 0, done.stderr)
        # 2 rad/s on 0.235 m wheels for 3 s: the front moves about 1.4 m
        # from its start at x = 0.35.
        x = float(done.stdout.split("x = ")[1].split()[0])
        self.assertAlmostEqual(x - 0.35, 1.41, delta=0.15)

    def test_lockstep_stop_at_wall(self):
        url = unique_url(21)
        done = self.run_python(url, [SOURCE_DIR + "/examples/lockstep_stop_at_wall.py", "--lcm-url", url],
                               "scanner_wall.xml", ["--startPaused=1", "--speed=0"])
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("stopped at tick", done.stdout)
        scanner = float(done.stdout.split("scanner ")[1].split()[0])
        self.assertAlmostEqual(scanner, 1.0, delta=0.01)


# A batch's controller that starts examples/lockstep_stop_at_wall.py again
# with the sanitizer runtime preloaded when the tree is sanitized: the
# batch's own environment cannot hold it (child_env()), so the test hands
# it over in variables of its own.
BATCH_CONTROLLER = """import os, sys
preload = os.environ.pop("SP_CONTROLLER_PRELOAD", "")
if preload:
    os.environ["LD_PRELOAD"] = preload
    os.environ["ASAN_OPTIONS"] = os.environ.pop("SP_CONTROLLER_ASAN_OPTIONS", "")
os.execv(sys.executable, [sys.executable, %r] + sys.argv[1:])
"""

BATCH_FILE = """<?xml version="1.0"?>
<batch name="python_controller" version="1">
  <world>scanner_wall.xml</world>
  <duration>0.5</duration>
  <controller>python3 %s --lcm-url {url}</controller>
  <seeds>1 2</seeds>
</batch>
"""


class BatchTest(unittest.TestCase):
    """simpartner-batch runs a Python controller given as `python3
    controller.py`: python3 is found on PATH as a shell finds it."""

    def test_a_controller_started_as_python3(self):
        work = tempfile.mkdtemp(prefix="sp_pybatch_")
        try:
            controller = os.path.join(work, "controller.py")
            with open(controller, "w") as f:
                f.write(BATCH_CONTROLLER % (SOURCE_DIR + "/examples/lockstep_stop_at_wall.py"))
            batch = os.path.join(work, "batch.xml")
            with open(batch, "w") as f:
                f.write(BATCH_FILE % controller)
            env = child_env()
            # This interpreter's folder first: another python3 earlier on
            # PATH (pyenv's) has no numpy.
            env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
            env["SP_CONTROLLER_PRELOAD"] = os.environ.get("LD_PRELOAD", "")
            env["SP_CONTROLLER_ASAN_OPTIONS"] = os.environ.get("ASAN_OPTIONS", "")
            checked = subprocess.run([BINARY_DIR + "/batch/simpartner-batch", batch, "--check"],
                                     env=env, capture_output=True, text=True, timeout=60)
            self.assertEqual(checked.returncode, 0, checked.stdout + checked.stderr)
            done = subprocess.run(
                [BINARY_DIR + "/batch/simpartner-batch", batch, "--results",
                 os.path.join(work, "results"), "--no-log", "--parallel", "2", "--quiet"],
                env=env, capture_output=True, text=True, timeout=300)
            self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
            self.assertIn("2 run(s) done, 0 failed", done.stdout)
        finally:
            shutil.rmtree(work, ignore_errors=True)


class DatabaseTest(unittest.TestCase):
    """read_logged: a run logged by a real simpartner-logger into a private server."""

    def test_read_a_logged_run(self):
        # Everything that can fail before the try comes before the server
        # starts: the finally below is what stops it.
        url = unique_url(3)
        work = tempfile.mkdtemp(prefix="sp_pydb_")
        server = os.path.join(work, "db")
        script = SOURCE_DIR + "/scripts/mariadb"
        subprocess.run([script, "start", "--datadir", server], check=True, env=child_env(),
                       stdout=subprocess.DEVNULL)
        logger_log = open(os.path.join(work, "logger.log"), "w")
        sim_log = open(os.path.join(work, "sim.log"), "w")
        logger = sim_process = None
        try:
            logger = subprocess.Popen(
                [BINARY_DIR + "/logger/simpartner-logger", "--params", "/dev/null",
                 "--lcm-url", url, "--db-options", server + "/logger.cnf",
                 "--spool", os.path.join(work, "spool")],
                stdout=logger_log, stderr=subprocess.STDOUT, env=child_env())
            deadline = time.time() + 30
            while ": logging udpm://" not in read(logger_log.name):
                self.assertLess(time.time(), deadline, read(logger_log.name))
                time.sleep(0.1)
            sim_process = start_sim(url, sim_log, ["--duration=2", "--engine=ode"])
            drive = simpartner.Sim(url, timeout=30)
            drive.set_velocity("Axle1Motor", [3.0])
            self.assertEqual(sim_process.wait(60), 0)
            del drive
            logger.terminate()
            self.assertEqual(logger.wait(120), 0, read(logger_log.name))
            run = simpartner.read_logged("last", db_options=server + "/reader.cnf")
            steps = len(run["time"])
            self.assertGreater(steps, 100)
            self.assertEqual(run["engine"], "ode")  # the sim's --engine
            self.assertTrue(np.all(np.diff(run["time"]) > 0))
            self.assertEqual(run["bodies"]["Wheel1"].shape, (steps, 7))
            self.assertEqual(run["joints"]["Axle1"].shape, (steps, 15))
            # The continuous angle is the integral of the logged rate.
            columns = run["joint_columns"]
            angle = run["joints"]["Axle1"][:, columns.index("angle")]
            rate = run["joints"]["Axle1"][:, columns.index("rate")]
            integral = np.concatenate([[0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(run["time"]))])
            self.assertLess(np.max(np.abs((angle - angle[0]) - integral)), 0.05)
            self.assertGreater(abs(angle[-1] - angle[0]), 2.0)
            with_v = simpartner.read_logged(str(run["simulation"]), db_options=server + "/reader.cnf",
                                            velocities=True)
            self.assertEqual(with_v["bodies"]["Wheel1"].shape, (steps, 10))
            with self.assertRaises(simpartner.DatabaseError) as caught:
                simpartner.read_logged("99", db_options=server + "/reader.cnf")
            self.assertIn("no simulation 99", str(caught.exception))
            self.check_selections(run, server + "/reader.cnf")
        finally:
            for p in (sim_process, logger):
                if p is not None:
                    stop(p)
            logger_log.close()
            sim_log.close()
            subprocess.run([script, "stop", "--datadir", server], env=child_env(),
                           stdout=subprocess.DEVNULL)
            shutil.rmtree(work, ignore_errors=True)

    def check_selections(self, run, options):
        """The id as a number, a time range, bodies and joints by name, forces."""
        steps = len(run["time"])
        self.assertEqual(run["step"].shape, (steps,))
        by_id = simpartner.read_logged(run["simulation"], db_options=options)
        self.assertTrue(np.array_equal(by_id["time"], run["time"]))
        by_numpy_id = simpartner.read_logged(np.int64(run["simulation"]), db_options=options)
        self.assertTrue(np.array_equal(by_numpy_id["step"], run["step"]))
        for wrong in (1.5, True, None):
            with self.assertRaises(TypeError):
                simpartner.read_logged(wrong, db_options=options)
        with self.assertRaises(simpartner.DatabaseError) as caught:
            simpartner.read_logged(0, db_options=options)
        self.assertIn("is not a simulationID", str(caught.exception))
        # The steps from 0.5 s to 1 s, with the whole run's numbers.
        part = simpartner.read_logged(run["simulation"], db_options=options, start=0.5, end=1.0)
        inside = (run["time"] >= 0.5) & (run["time"] <= 1.0)
        self.assertGreater(np.count_nonzero(inside), 100)
        self.assertTrue(np.array_equal(part["time"], run["time"][inside]))
        self.assertTrue(np.array_equal(part["bodies"]["Wheel1"], run["bodies"]["Wheel1"][inside]))
        self.assertTrue(np.array_equal(part["joints"]["Axle1"], run["joints"]["Axle1"][inside]))
        # Only the bodies and joints named; contact forces on request.
        wheels = simpartner.read_logged(run["simulation"], db_options=options,
                                        bodies=["Wheel1", "Wheel2"], joints="Axle1", forces=True)
        self.assertEqual(sorted(wheels["bodies"]), ["Wheel1", "Wheel2"])
        self.assertEqual(list(wheels["joints"]), ["Axle1"])
        self.assertEqual(wheels["forces"]["Wheel1"].shape, (steps, 6))
        self.assertEqual(wheels["force_columns"][:3], ["Fx_N", "Fy_N", "Fz_N"])
        # The wheel stands on the ground (y up): pushed up at the end.
        self.assertGreater(wheels["forces"]["Wheel1"][-1, 1], 100.0)
        self.assertTrue(np.array_equal(wheels["bodies"]["Wheel2"], run["bodies"]["Wheel2"]))
        self.assertEqual(simpartner.read_logged(run["simulation"], db_options=options, bodies=[],
                                                joints=[])["bodies"], {})
        with self.assertRaises(simpartner.DatabaseError) as caught:
            simpartner.read_logged(run["simulation"], db_options=options, bodies="Wheel7")
        self.assertIn("no body named 'Wheel7'", str(caught.exception))
        with self.assertRaises(TypeError):
            simpartner.read_logged(run["simulation"], db_options=options, joints=3)


if __name__ == "__main__":
    unittest.main()
