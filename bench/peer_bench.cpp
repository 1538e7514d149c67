// Our sim next to MuJoCo 2.2 on the same WorkPartner, in one run: each
// robot (gen3, gen4 on flat ground) stands still for --stand seconds of sim
// time at 1 ms, then drives straight (all four wheels at 1.5 rad/s, SPEC 8's
// test-track speed, 0.3525 m/s without slip) for --drive seconds.
//   ours         sim::Simulation::Step (commands, controllers, ODE dWorldStep,
//                health check)
//   ours+pub     sim::SimNode: Step, SIM_STATE every step on LCM (udpm,
//                ttl 0) and the incoming side polled, as the process runs
//   ours QS20    bare, with ODE's iterative QuickStep (20 iterations)
//                instead of dWorldStep: what our own faster stepper gives
//   ours mj      Simulation::Step with --engine=mujoco (our MuJoCo engine:
//                the model built in memory, our contact, motor and stop
//                mappings, sim_core/src/mujoco_world.h)
//   ours mj+pub  the same through SimNode, publishing as the process runs
//   mujoco       the exported MJCF (simpartner-convert) through MuJoCo's C
//                API with its defaults (Euler, pyramidal cone, Newton)
//   mujoco acc   the same with settings at least as accurate as ours:
//                implicit integrator, elliptic cone, Newton to 1e-10,
//                noslip iterations (no creep of soft friction)
// --only bare runs our bare ODE stepping alone (for a profiler).
// Per setting: microseconds per step (whole run; this thread's CPU time,
// and wall time), the CPU time's ratio to ours, the
// summed vertical wheel contact force over the robot's weight (mean of the
// last standing second), the horizontal drift of the front chassis from 1 s
// (settled) to the end of standing, and the driving speed (from 1 s after
// the wheels start).
//   bench/peer_bench [--stand S] [--drive S] [--only ours|bare|mujoco] [--lcm-url URL]
#include <lcm/lcm-cpp.hpp>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/command_t.hpp"
#include "simpartner/convert/mjcf_export.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/sim_node.h"
#include "simpartner/sim/simulation.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace simpartner;

constexpr double kWheelSpeed = 1.5;  // [rad/s]
const char* const kWheels[] = {"Wheel1", "Wheel2", "Wheel3", "Wheel4"};
const char* const kWheelMotors[] = {"Axle1Motor", "Axle2Motor", "Axle3Motor", "Axle4Motor"};
const char* const kTrackedBody = "FrontChassis";
// The first second settles the robot onto its wheels and servos (MuJoCo's
// position servos sag by their load / kp); the drift counts from then.
constexpr double kSettle = 1.0;  // [s]

// CPU time of this thread: on a machine shared with builds, wall time
// per step depends on who else wants the cores; the CPU time a step costs
// barely does.
double ThreadCpuMicros() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e6 + static_cast<double>(now.tv_nsec) * 1e-3;
}

struct Figures {
  double micros_per_step = 0;         // thread CPU time
  double wall_micros_per_step = 0;
  double wheel_load_over_weight = 0;  // summed vertical wheel force / m g
  double drift_mm = 0;                // horizontal, over the standing phase
  double speed = 0;                   // [m/s] while driving (after 1 s)
  bool failed = false;
  std::string note;
};

struct Run {
  int stand_steps;
  int drive_steps;
  double dt;
};

// ---- ours --------------------------------------------------------------

void CommandWheels(sim::Simulation* sim, double speed) {
  for (const char* motor : kWheelMotors) {
    command_t command{};
    command.target = motor;
    command.action = command_t::ACTION_SET;
    command.apply_at_step = -1;
    command.values = {1000, speed};
    command.num_values = 2;
    if (auto refused = sim->Submit(command)) std::cerr << motor << ": " << refused->reason << "\n";
  }
}

Figures RunOurs(const model::World& world, const Run& run, lcm::LCM* bus,
                const std::string& engine = "ode", int quick_iterations = 0) {
  Parameters params;
  params.stepsize = run.dt;
  params.engine = engine;
  if (quick_iterations > 0) {
    params.stepper = "quick";
    params.quickStepIterations = quick_iterations;
  }
  sim::Simulation sim(world, params, 1);
  std::unique_ptr<sim::SimNode> node;
  if (bus != nullptr) node = std::make_unique<sim::SimNode>(&sim, bus);
  const double weight = world.robots.at(0).robot.TotalMass() * -world.gravity.y();
  const int tracked = sim.flat().FindBody("", kTrackedBody);
  std::vector<int> wheels;
  for (const char* wheel : kWheels) wheels.push_back(sim.flat().FindBody("", wheel));
  Figures figures;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  const int settled = static_cast<int>(std::lround(kSettle / run.dt));
  double load_sum = 0;
  int load_samples = 0;
  Eigen::Vector3d drive_from = Eigen::Vector3d::Zero();
  const int measure_from = run.stand_steps - static_cast<int>(std::lround(1.0 / run.dt));
  const int speed_from = run.stand_steps + static_cast<int>(std::lround(1.0 / run.dt));
  Clock::duration busy{};
  double cpu = 0;
  for (int n = 0; n < run.stand_steps + run.drive_steps; ++n) {
    if (n == settled) start = sim.engine().ReadBody(tracked).position;
    if (n == run.stand_steps) {
      const Eigen::Vector3d d = sim.engine().ReadBody(tracked).position - start;
      figures.drift_mm = std::hypot(d.x(), d.z()) * 1000;
      CommandWheels(&sim, kWheelSpeed);
    }
    if (n == speed_from) drive_from = sim.engine().ReadBody(tracked).position;
    const auto begin = Clock::now();
    const double cpu_begin = ThreadCpuMicros();
    if (node) {
      node->HandleIncoming(Clock::duration::zero());
      node->StepAndPublish();
    } else if (!sim.Step()) {
      figures.failed = true;
    }
    cpu += ThreadCpuMicros() - cpu_begin;
    busy += Clock::now() - begin;
    if (sim.faulted()) {
      figures.failed = true;
      break;
    }
    if (n >= measure_from && n < run.stand_steps) {
      double vertical = 0;
      for (int wheel : wheels) vertical += sim.engine().ReadBody(wheel).contact_force.y();
      load_sum += vertical;
      ++load_samples;
    }
  }
  figures.wall_micros_per_step = std::chrono::duration<double, std::micro>(busy).count() /
                                 (run.stand_steps + run.drive_steps);
  figures.micros_per_step = cpu / (run.stand_steps + run.drive_steps);
  figures.wheel_load_over_weight = load_sum / std::max(load_samples, 1) / weight;
  const Eigen::Vector3d driven = sim.engine().ReadBody(tracked).position - drive_from;
  const double drive_time = (run.stand_steps + run.drive_steps - speed_from) * run.dt;
  figures.speed = drive_time > 0 ? std::hypot(driven.x(), driven.z()) / drive_time : 0;
  return figures;
}

// ---- MuJoCo ------------------------------------------------------------

struct MjModelFree {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataFree {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

std::unique_ptr<mjModel, MjModelFree> LoadMjcf(const std::string& xml) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("peer_bench_" + std::to_string(getpid()) + ".xml"))
                               .string();
  std::ofstream(path) << xml;
  char error[1000] = "";
  std::unique_ptr<mjModel, MjModelFree> m(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  std::filesystem::remove(path);
  if (!m) std::cerr << "peer_bench: MuJoCo refused the exported MJCF: " << error << "\n";
  return m;
}

Figures RunMujoco(const model::World& world, const Run& run, bool accurate) {
  Figures figures;
  Parameters params;
  params.stepsize = run.dt;
  auto m = LoadMjcf(convert::ExportMjcf(world, params).xml);
  if (!m) {
    figures.failed = true;
    return figures;
  }
  if (accurate) {
    m->opt.integrator = mjINT_IMPLICIT;
    m->opt.cone = mjCONE_ELLIPTIC;
    m->opt.solver = mjSOL_NEWTON;
    m->opt.iterations = 200;
    m->opt.tolerance = 1e-10;
    m->opt.noslip_iterations = 10;
  }
  std::unique_ptr<mjData, MjDataFree> d(mj_makeData(m.get()));
  const double weight = world.robots.at(0).robot.TotalMass() * -world.gravity.y();
  const int tracked = mj_name2id(m.get(), mjOBJ_BODY, kTrackedBody);
  std::vector<int> wheel_bodies;
  for (const char* wheel : kWheels) wheel_bodies.push_back(mj_name2id(m.get(), mjOBJ_BODY, wheel));
  std::vector<int> wheel_motors;
  for (const char* motor : kWheelMotors)
    wheel_motors.push_back(mj_name2id(m.get(), mjOBJ_ACTUATOR, motor));
  // Every position servo holds the file's pose (joint value 0), as ours do.
  for (int u = 0; u < m->nu; ++u) d->ctrl[u] = 0;
  mj_forward(m.get(), d.get());
  auto horizontal = [&](int body) {
    return Eigen::Vector2d(d->xpos[3 * body], d->xpos[3 * body + 1]);
  };
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  const int settled = static_cast<int>(std::lround(kSettle / run.dt));
  Eigen::Vector2d drive_from = Eigen::Vector2d::Zero();
  const int measure_from = run.stand_steps - static_cast<int>(std::lround(1.0 / run.dt));
  const int speed_from = run.stand_steps + static_cast<int>(std::lround(1.0 / run.dt));
  double load_sum = 0;
  int load_samples = 0;
  Clock::duration busy{};
  double cpu = 0;
  for (int n = 0; n < run.stand_steps + run.drive_steps; ++n) {
    if (n == settled) start = horizontal(tracked);
    if (n == run.stand_steps) {
      figures.drift_mm = (horizontal(tracked) - start).norm() * 1000;
      for (int motor : wheel_motors) d->ctrl[motor] = kWheelSpeed;
    }
    if (n == speed_from) drive_from = horizontal(tracked);
    const auto begin = Clock::now();
    const double cpu_begin = ThreadCpuMicros();
    mj_step(m.get(), d.get());
    cpu += ThreadCpuMicros() - cpu_begin;
    busy += Clock::now() - begin;
    if (n >= measure_from && n < run.stand_steps) {
      // Vertical force of every wheel contact (the contact frame's rows
      // are its axes in the world; its force is along them).
      double vertical = 0;
      for (int c = 0; c < d->ncon; ++c) {
        const mjContact& contact = d->contact[c];
        const int b1 = m->geom_bodyid[contact.geom1], b2 = m->geom_bodyid[contact.geom2];
        bool wheel = false;
        for (int w : wheel_bodies) wheel = wheel || w == b1 || w == b2;
        if (!wheel) continue;
        mjtNum force[6];
        mj_contactForce(m.get(), d.get(), c, force);
        double z = 0;
        for (int k = 0; k < 3; ++k) z += force[k] * contact.frame[3 * k + 2];
        vertical += std::abs(z);
      }
      load_sum += vertical;
      ++load_samples;
    }
    for (int k = 0; k < m->nq; ++k) {
      if (!std::isfinite(d->qpos[k])) {
        figures.failed = true;
        break;
      }
    }
    if (figures.failed) break;
  }
  figures.wall_micros_per_step = std::chrono::duration<double, std::micro>(busy).count() /
                                 (run.stand_steps + run.drive_steps);
  figures.micros_per_step = cpu / (run.stand_steps + run.drive_steps);
  figures.wheel_load_over_weight = load_sum / std::max(load_samples, 1) / weight;
  const double drive_time = (run.stand_steps + run.drive_steps - speed_from) * run.dt;
  figures.speed = drive_time > 0 ? (horizontal(tracked) - drive_from).norm() / drive_time : 0;
  return figures;
}

void Print(const std::string& world, const char* setting, const Figures& f, double ours_us) {
  std::printf("%-21s %-11s %9.1f %9.1f %8.3f %10.4f %9.2f %9.4f%s\n", world.c_str(), setting,
              f.micros_per_step, f.wall_micros_per_step, f.micros_per_step / ours_us,
              f.wheel_load_over_weight, f.drift_mm, f.speed,
              f.failed ? "  FAILED (non-finite or faulted)" : "");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  simpartner::CommandLineSpec spec;
  spec.program = "peer_bench";
  spec.summary =
      "WorkPartner gen3 and gen4 on flat ground, 1 ms steps: stand still, then drive straight\n"
      "with the wheels at 1.5 rad/s, in our sim on ODE and on our MuJoCo engine (bare\n"
      "Simulation::Step; SimNode publishing on LCM) and in MuJoCo 2.2 on the exported MJCF\n"
      "(default settings; accurate settings).\n"
      "Prints us/step, the ratio to ours, wheel load / weight, standing drift [mm], speed [m/s].";
  spec.options = {
      simpartner::Number("stand", "SECONDS", "standing time, at least 2 (default 20)"),
      simpartner::Number("drive", "SECONDS", "driving time (default 5)"),
      simpartner::Text("only", "ours|bare|mujoco", "run only these rows"),
      simpartner::Text("lcm-url", "URL", "LCM URL of ours+pub (default udpm://239.255.76.67:7667?ttl=0)"),
  };
  simpartner::CommandLine args;
  if (const auto done =
          simpartner::ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  const double stand = args.Number("stand", 20), drive = args.Number("drive", 5);
  const std::string only = args.Text("only", "");
  const std::string url = args.Text("lcm-url", "udpm://239.255.76.67:7667?ttl=0");
  if (!(stand >= 2.0) || !(drive >= 0.0) ||
      (!only.empty() && only != "ours" && only != "bare" && only != "mujoco")) {
    std::cerr << "peer_bench: --stand needs >= 2 s, --drive >= 0, --only ours, bare or mujoco\n";
    return 2;
  }
  const Run run{static_cast<int>(std::lround(stand / 0.001)),
                static_cast<int>(std::lround(drive / 0.001)), 0.001};
  lcm::LCM bus(url);
  if (!bus.good()) {
    std::cerr << "peer_bench: cannot open LCM at " << url << "\n";
    return 1;
  }
  std::printf("%-21s %-11s %9s %9s %8s %10s %9s %9s\n", "world", "setting", "cpu us", "wall us",
              "cpu/ours", "wheels/mg", "drift mm", "speed m/s");
  for (const char* file : {"flat_ground.xml", "gen4_flat.xml"}) {
    const std::string path = std::string(SP_SOURCE_DIR) + "/models/worlds/" + file;
    model::WorldLoadResult loaded = model::LoadWorldFile(path);
    if (!loaded.world) {
      std::cerr << loaded.diagnostics.Format() << "\n";
      return 1;
    }
    const std::string name = std::string(file == std::string("flat_ground.xml") ? "gen3 " : "gen4 ") +
                             file;
    double ours_us = 1;
    if (only != "mujoco") {
      const Figures ours = RunOurs(*loaded.world, run, nullptr);
      ours_us = ours.micros_per_step;
      Print(name, "ours", ours, ours_us);
      if (only != "bare") {
        Print(name, "ours+pub", RunOurs(*loaded.world, run, &bus), ours_us);
        Print(name, "ours QS20", RunOurs(*loaded.world, run, nullptr, "ode", 20), ours_us);
        Print(name, "ours mj", RunOurs(*loaded.world, run, nullptr, "mujoco"), ours_us);
        Print(name, "ours mj+pub", RunOurs(*loaded.world, run, &bus, "mujoco"), ours_us);
      }
    }
    if (only.empty() || only == "mujoco") {
      Print(name, "mujoco", RunMujoco(*loaded.world, run, false), ours_us);
      Print(name, "mujoco acc", RunMujoco(*loaded.world, run, true), ours_us);
    }
  }
  return 0;
}
