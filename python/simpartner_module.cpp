// The `simpartner` Python module: the client library (connect to a sim on
// the bus, its model, the newest state as NumPy arrays, commands, run
// control, waiting for sim time) and the logger's query library (a logged
// simulation from the database as NumPy arrays). The client's typed errors
// become Python exceptions of the same names (subclasses of
// simpartner.ClientError); database and request errors are
// simpartner.DatabaseError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/client/client.h"
#include "simpartner/client/command.h"
#include "simpartner/client/lock_step.h"
#include "simpartner/command_shape.h"
#include "simpartner/image_fit.h"
#include "simpartner/logger/export.h"
#include "simpartner/logger/logged_run.h"
#include "simpartner/parameters.h"
#include "simpartner/sensor_kinds.h"

namespace py = pybind11;

namespace {

using simpartner::client::Client;
using simpartner::client::ClientOptions;

// An (rows, columns) float64 array.
py::array_t<double> Matrix(size_t rows, size_t columns) {
  return py::array_t<double>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(columns)});
}

// An array of `shape` (row-major) that owns `values`: no copy.
template <class T>
py::array_t<T> OwningArray(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule release(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::move(shape), owner->data(), release);
}

// The wheels on soil of a state as a dict of arrays, one row per wheel
// (body: its index in the model's bodies); rows 0 on rigid ground.
py::dict WheelSoilDict(const simpartner::state_t& s) {
  const size_t n = s.wheel_soil.size();
  py::array_t<int32_t> body(static_cast<py::ssize_t>(n));
  py::array_t<bool> stuck(static_cast<py::ssize_t>(n));
  py::array_t<double> sinkage(static_cast<py::ssize_t>(n)), slip(static_cast<py::ssize_t>(n)),
      thrust(static_cast<py::ssize_t>(n)), drawbar(static_cast<py::ssize_t>(n)),
      load(static_cast<py::ssize_t>(n)), torque(static_cast<py::ssize_t>(n));
  auto normal = Matrix(n, 3), shear = Matrix(n, 3);
  auto nf = normal.mutable_unchecked<2>();
  auto sf = shear.mutable_unchecked<2>();
  for (size_t i = 0; i < n; ++i) {
    const auto& w = s.wheel_soil[i];
    const auto r = static_cast<py::ssize_t>(i);
    body.mutable_at(r) = w.body;
    stuck.mutable_at(r) = w.stuck;
    sinkage.mutable_at(r) = w.sinkage;
    slip.mutable_at(r) = w.slip;
    thrust.mutable_at(r) = w.thrust;
    drawbar.mutable_at(r) = w.drawbar_pull;
    load.mutable_at(r) = w.load;
    torque.mutable_at(r) = w.axle_torque;
    for (py::ssize_t k = 0; k < 3; ++k) {
      nf(r, k) = w.normal_force[k];
      sf(r, k) = w.shear_force[k];
    }
  }
  py::dict d;
  d["body"] = body;
  d["sinkage"] = sinkage;
  d["slip"] = slip;
  d["normal_force"] = normal;
  d["shear_force"] = shear;
  d["thrust"] = thrust;
  d["drawbar_pull"] = drawbar;
  d["load"] = load;
  d["axle_torque"] = torque;
  d["stuck"] = stuck;
  return d;
}

// The newest state as a dict of arrays (bodies and joints in model order).
py::dict StateDict(const simpartner::state_t& s) {
  const size_t nb = s.bodies.size(), nj = s.joints.size();
  auto position = Matrix(nb, 3), orientation = Matrix(nb, 4), velocity = Matrix(nb, 3),
       angular = Matrix(nb, 3), contact = Matrix(nb, 3);
  auto p = position.mutable_unchecked<2>();
  auto q = orientation.mutable_unchecked<2>();
  auto v = velocity.mutable_unchecked<2>();
  auto w = angular.mutable_unchecked<2>();
  auto f = contact.mutable_unchecked<2>();
  for (size_t i = 0; i < nb; ++i) {
    const auto& b = s.bodies[i];
    const auto r = static_cast<py::ssize_t>(i);
    for (py::ssize_t k = 0; k < 3; ++k) {
      p(r, k) = b.position[k];
      v(r, k) = b.linear_velocity[k];
      w(r, k) = b.angular_velocity[k];
      f(r, k) = b.contact_force[k];
    }
    for (py::ssize_t k = 0; k < 4; ++k) q(r, k) = b.orientation[k];
  }
  auto angle = Matrix(nj, 3), continuous = Matrix(nj, 3), rate = Matrix(nj, 3),
       force1 = Matrix(nj, 3);
  auto a = angle.mutable_unchecked<2>();
  auto c = continuous.mutable_unchecked<2>();
  auto rt = rate.mutable_unchecked<2>();
  auto f1 = force1.mutable_unchecked<2>();
  for (size_t i = 0; i < nj; ++i) {
    const auto& j = s.joints[i];
    const auto r = static_cast<py::ssize_t>(i);
    for (py::ssize_t k = 0; k < 3; ++k) {
      a(r, k) = j.position[k];
      c(r, k) = j.continuous_position[k];
      rt(r, k) = j.rate[k];
      f1(r, k) = j.force1[k];
    }
  }
  py::dict d;
  d["step"] = s.step;
  d["time"] = s.sim_time;
  d["simulation_id"] = s.simulation_id;
  d["position"] = position;
  d["orientation"] = orientation;
  d["velocity"] = velocity;
  d["angular_velocity"] = angular;
  d["contact_force"] = contact;
  d["joint_angle"] = angle;
  d["joint_continuous_angle"] = continuous;
  d["joint_rate"] = rate;
  d["joint_force1"] = force1;
  d["wheel_soil"] = WheelSoilDict(s);
  return d;
}

class Sim {
 public:
  Sim(const std::string& url, double timeout, const std::string& program) {
    ClientOptions options;
    options.url = url;
    options.model_timeout = timeout;
    options.program = program;
    py::gil_scoped_release release;
    client_ = std::make_unique<Client>(options);
  }
  Client& client() { return *client_; }

  py::dict Model() const {
    const auto catalog = client_->catalog();
    py::dict d;
    d["simulation_id"] = catalog->simulation_id();
    d["world"] = catalog->world_name();
    d["step_size"] = catalog->step_size();
    d["robots"] = catalog->robot_names();
    d["bodies"] = catalog->body_names();
    d["joints"] = catalog->joint_names();
    py::list targets;
    for (const auto& t : catalog->targets()) {
      py::dict target;
      target["name"] = t.name;
      target["robot"] = t.robot;
      target["kind"] = t.is_actuator() ? "actuator" : "sensor";
      target["type"] = t.kind_name();
      target["joint"] = t.joint;
      target["axes"] = t.num_axes;
      targets.append(target);
    }
    d["targets"] = targets;
    return d;
  }

  py::dict WaitUntil(double sim_time, double timeout) {
    simpartner::state_t s;
    {
      py::gil_scoped_release release;
      s = client_->WaitUntilSimTime(sim_time, timeout);
    }
    return StateDict(s);
  }

  // The step the command applies in: at once (waiting for the sim's
  // reply), or in lock-step the tick it answers (its reply comes with the
  // next tick, which raises Refused if the sim refused it).
  int64_t Send(const simpartner::command_t& command, double timeout) {
    py::gil_scoped_release release;
    const int64_t tick = client_->LockStepTick();
    if (tick >= 0) {
      client_->Send(command);
      return tick;
    }
    return client_->Command(command, timeout).applied_at_step;
  }

  // The newest state, or (none yet: a paused sim sends none) the state the
  // sim answers a request with.
  py::dict State(double timeout) const {
    std::optional<simpartner::state_t> s = client_->LatestState();
    if (!s) {
      py::gil_scoped_release release;
      s = client_->RequestState(timeout);
    }
    return StateDict(*s);
  }

 private:
  std::unique_ptr<Client> client_;
};

// A sensor reading as a dict: values as a NumPy float64 array in the
// layout of sensor_reading_t.lcm (1-D; a Lidar's layers x rays), their
// names (sensor_kinds.h), the Echo's text.
py::dict ReadingDict(const simpartner::sensor_reading_t& r, const simpartner::model_t& model) {
  const simpartner::sensor_t* sensor =
      r.sensor >= 0 && static_cast<size_t>(r.sensor) < model.sensors.size()
          ? &model.sensors[static_cast<size_t>(r.sensor)]
          : nullptr;
  const simpartner::ReadingShape shape =
      sensor ? simpartner::ShapeOfReading(*sensor) : simpartner::ReadingShape{};
  std::vector<double> values = r.values;
  std::vector<py::ssize_t> dims = {static_cast<py::ssize_t>(values.size())};
  if (sensor && sensor->kind == simpartner::sensor_t::KIND_LIDAR &&
      static_cast<size_t>(shape.rows) * static_cast<size_t>(shape.columns) == values.size())
    dims = {shape.rows, shape.columns};
  py::dict d;
  d["name"] = r.name;
  d["kind"] = simpartner::SpellSensorKind(r.kind).word;
  d["step"] = r.step;
  d["time"] = r.sim_time;
  d["values"] = OwningArray(std::move(values), std::move(dims));
  d["columns"] = sensor ? simpartner::ReadingColumns(*sensor) : std::vector<std::string>{};
  d["text"] = r.text;
  return d;
}

// A camera image as a dict: pixels as a NumPy array (H x W x 3 uint8 for
// colour; H x W float32 metres or uint16 millimetres for depth), without
// going through Python objects per pixel.
py::dict ImageDict(simpartner::image_t image) {
  const py::ssize_t h = image.height, w = image.width;
  py::object pixels;
  if (image.format == simpartner::image_t::FORMAT_RGB8) {
    pixels = OwningArray(std::move(image.data), {h, w, 3});
  } else if (image.format == simpartner::image_t::FORMAT_DEPTH_F32) {
    std::vector<float> depth(image.data.size() / sizeof(float));
    std::memcpy(depth.data(), image.data.data(), depth.size() * sizeof(float));  // little-endian
    pixels = OwningArray(std::move(depth), {h, w});
  } else {
    std::vector<uint16_t> depth(image.data.size() / sizeof(uint16_t));
    std::memcpy(depth.data(), image.data.data(), depth.size() * sizeof(uint16_t));
    pixels = OwningArray(std::move(depth), {h, w});
  }
  py::dict d;
  d["name"] = image.name;
  d["robot"] = image.robot;
  d["step"] = image.step;
  d["time"] = image.sim_time;
  d["width"] = image.width;
  d["height"] = image.height;
  d["format"] = simpartner::ImageFormatName(image.format);
  d["pixels"] = pixels;
  return d;
}

simpartner::client::ImageKind ImageKindOf(bool depth) {
  return depth ? simpartner::client::ImageKind::kDepth : simpartner::client::ImageKind::kColour;
}

// for state in sim.lockstep(period, steps): the client library's LockStep
// as a Python iterator (and context manager). It leaves lock-step when the
// loop ends, breaks or raises (the iterator is dropped), or on close().
class LockStepLoop {
 public:
  LockStepLoop(Sim& sim, int64_t period, std::optional<int64_t> steps, const std::string& name,
               bool resume, double timeout)
      : steps_(steps) {
    simpartner::client::LockStepOptions options;
    options.period = period;
    options.name = name;
    options.resume = resume;
    options.timeout = timeout;
    py::gil_scoped_release release;
    loop_ = std::make_unique<simpartner::client::LockStep>(sim.client(), options);
  }

  py::dict Next() {
    if (!loop_ || (steps_ && taken_ >= *steps_)) {
      Close();
      throw py::stop_iteration();
    }
    simpartner::state_t state;
    try {
      py::gil_scoped_release release;
      state = loop_->Next();
    } catch (const simpartner::client::SimStopped&) {
      Close();  // the sim ended (its duration reached): so does the loop
      throw py::stop_iteration();
    }
    ++taken_;
    return StateDict(state);
  }

  void Close() {
    py::gil_scoped_release release;
    loop_.reset();
  }

  int64_t tick() const { return loop_ ? loop_->tick() : -1; }

 private:
  std::optional<int64_t> steps_;  // ticks to take; none: until the loop is left
  int64_t taken_ = 0;
  std::unique_ptr<simpartner::client::LockStep> loop_;
};

// read_logged's `simulation`: an id (int, or a NumPy integer), "last",
// "running", or the id as text.
std::string SimulationArgument(const py::object& simulation) {
  if (py::isinstance<py::str>(simulation)) return simulation.cast<std::string>();
  if (!py::isinstance<py::bool_>(simulation) && PyIndex_Check(simulation.ptr())) {
    const auto id = py::reinterpret_steal<py::int_>(PyNumber_Index(simulation.ptr()));
    if (!id) throw py::error_already_set();
    return std::to_string(id.cast<long long>());
  }
  throw py::type_error(
      "read_logged: simulation must be a simulation id (int), 'last' or 'running', not " +
      std::string(py::str(py::type::handle_of(simulation).attr("__name__"))));
}

// read_logged's `bodies` or `joints`: None (all), a name or a list of names.
simpartner::logger::PartSelection SelectionArgument(const py::object& names, const char* what) {
  if (names.is_none()) return {};
  if (py::isinstance<py::str>(names)) return {false, {names.cast<std::string>()}};
  try {
    return {false, names.cast<std::vector<std::string>>()};
  } catch (const py::cast_error&) {
    throw py::type_error(std::string("read_logged: ") + what +
                         " must be None, a name or a list of names");
  }
}

py::dict PartDict(std::vector<simpartner::logger::PartArray>* parts, size_t steps) {
  py::dict out;
  for (auto& part : *parts) {
    const size_t columns = steps ? part.values.size() / steps : 0;
    out[py::str(part.name)] = OwningArray(std::move(part.values), {static_cast<py::ssize_t>(steps),
                                                                   static_cast<py::ssize_t>(columns)});
  }
  return out;
}

std::vector<std::string> ColumnNames(simpartner::logger::ExportKind kind, bool velocities) {
  simpartner::logger::ExportRequest request;
  request.kind = kind;
  request.velocities = velocities;
  return simpartner::logger::ExportColumns(request);
}

// A logged simulation of the database: per body and joint arrays over the
// logged steps (logged_run.h reads them).
py::dict ReadLogged(const py::object& simulation, const std::string& db_options,
                    const std::string& dbname, const std::string& dbserver, bool velocities,
                    std::optional<double> start, std::optional<double> end, const py::object& bodies,
                    const py::object& joints, bool forces) {
  using namespace simpartner::logger;
  LoggedRunRequest request;
  request.simulation = SimulationArgument(simulation);
  if (start) request.from = *start;
  if (end) request.to = *end;
  request.bodies = SelectionArgument(bodies, "bodies");
  request.joints = SelectionArgument(joints, "joints");
  request.velocities = velocities;
  request.forces = forces;
  simpartner::Parameters params;
  std::vector<std::string> warnings;
  params.dbname = dbname;
  params.dbserver = dbserver;
  const DbTarget target = ResolveDbTarget(params, db_options, kPrivateReaderOptions, &warnings);
  LoggedRun run;
  {
    py::gil_scoped_release release;
    std::unique_ptr<DbConnection> db = DbConnection::Open(target, false);
    db->UseDatabase(false);
    run = ReadLoggedRun(db.get(), request);
    db.reset();
    DbThreadEnd();
  }
  const size_t steps = run.time.size();
  py::dict result;
  result["simulation"] = run.simulation;
  result["engine"] = run.engine;
  result["time"] = OwningArray(std::move(run.time), {static_cast<py::ssize_t>(steps)});
  result["step"] = OwningArray(std::move(run.step), {static_cast<py::ssize_t>(steps)});
  result["bodies"] = PartDict(&run.poses, steps);
  result["joints"] = PartDict(&run.joints, steps);
  result["forces"] = PartDict(&run.forces, steps);
  result["body_columns"] = ColumnNames(ExportKind::kPoses, velocities);
  result["joint_columns"] = ColumnNames(ExportKind::kJoints, false);
  result["force_columns"] = ColumnNames(ExportKind::kForces, false);
  return result;
}

// Refuses an interpreter the module cannot work in, at import and naming
// the one it was built for (SP_PYTHON_EXECUTABLE, python/CMakeLists.txt).
// Another python3 first on PATH (a pyenv shim) of the same version loads
// the module, whose ABI tag it shares, but has no Debian numpy: without
// this check the import succeeded and the first array failed.
void RequireTheInterpreterBuiltFor() {
  const py::module_ sys = py::module_::import("sys");
  const py::tuple version = sys.attr("version_info");
  const std::string running = py::str(sys.attr("executable")).cast<std::string>() + " (Python " +
                              py::str(version[0]).cast<std::string>() + "." +
                              py::str(version[1]).cast<std::string>() + "." +
                              py::str(version[2]).cast<std::string>() + ")";
  std::string problem;
  if (version[0].cast<int>() != PY_MAJOR_VERSION || version[1].cast<int>() != PY_MINOR_VERSION) {
    problem = "is not Python " + std::to_string(PY_MAJOR_VERSION) + "." +
              std::to_string(PY_MINOR_VERSION);
  } else {
    try {
      py::module_::import("numpy");
    } catch (const py::error_already_set& e) {
      problem = "cannot import numpy, which the module's arrays need (" +
                py::str(e.value()).cast<std::string>() + ")";
    }
  }
  if (!problem.empty())
    throw py::import_error("simpartner was built for " SP_PYTHON_EXECUTABLE
                           " (Python " SP_PYTHON_VERSION "); this interpreter, " +
                           running + ", " + problem + ". Run it with " SP_PYTHON_EXECUTABLE ".");
}

}  // namespace

PYBIND11_MODULE(simpartner, m) {
  RequireTheInterpreterBuiltFor();
  m.doc() = "SimPartner: drive a running simpartner-sim over LCM and read logged simulations";
  m.attr("BUILT_FOR_PYTHON") = SP_PYTHON_EXECUTABLE;
  namespace client = simpartner::client;
  auto client_error = py::register_exception<client::ClientError>(m, "ClientError", PyExc_RuntimeError);
  // The subclasses: registered after the base so that each maps to its own.
  py::register_exception<client::UnknownTarget>(m, "UnknownTarget", client_error.ptr());
  py::register_exception<client::Refused>(m, "Refused", client_error.ptr());
  py::register_exception<client::Timeout>(m, "Timeout", client_error.ptr());
  py::register_exception<client::NoSim>(m, "NoSim", client_error.ptr());
  py::register_exception<client::SimRestarted>(m, "SimRestarted", client_error.ptr());
  py::register_exception<client::BadValues>(m, "BadValues", client_error.ptr());
  py::register_exception<client::LockStepError>(m, "LockStepError", client_error.ptr());
  py::register_exception<client::SimStopped>(m, "SimStopped", client_error.ptr());
  py::register_exception<simpartner::Error>(m, "DatabaseError", PyExc_RuntimeError);
  m.attr("DEFAULT_URL") = client::kDefaultUrl;

  py::class_<Sim>(m, "Sim", "A connection to the sim on the bus (the client library's Client).")
      .def(py::init<const std::string&, double, const std::string&>(), py::arg("url") = client::kDefaultUrl,
           py::arg("timeout") = 3.0, py::arg("program") = "python",
           "Connects and learns the model; NoSim when no sim answers within timeout s.")
      .def_property_readonly("url", [](Sim& s) { return s.client().url(); })
      .def("model", &Sim::Model, "dict: simulation_id, world, step_size, robots, bodies, joints, "
                                 "targets (name, robot, kind, type, joint, axes)")
      .def("state", &Sim::State, py::arg("timeout") = 2.0,
           "The newest state (dict of NumPy arrays; wheel_soil: one row per wheel on soft soil); "
           "before any (a paused sim sends none) the state the sim answers a request with; Timeout")
      .def(
          "reading",
          [](Sim& s, const std::string& name) -> py::object {
            s.client().Find(name);  // UnknownTarget for a name the model lacks
            const auto r = s.client().LatestReading(name);
            if (!r) return py::none();
            return ReadingDict(*r, *s.client().model());
          },
          py::arg("name"),
          "The latest reading of sensor `name`, or None before the first: dict of name, kind "
          "('imu', 'lidar', ...), step, time [s of sim time], values (NumPy float64: 1-D in the "
          "order of columns; a lidar's 2-D, layers x rays, lowest layer first), columns (the "
          "names of the values: 'ax', 'ay', ... or 'range_0', ...), text (an echo's)")
      .def(
          "wait_reading",
          [](Sim& s, const std::string& name, int64_t after_step, double timeout) {
            simpartner::sensor_reading_t r;
            {
              py::gil_scoped_release release;
              r = s.client().WaitForReading(name, after_step, timeout);
            }
            return ReadingDict(r, *s.client().model());
          },
          py::arg("name"), py::arg("after_step") = -1, py::arg("timeout") = 2.0,
          "Waits for a reading of sensor `name` from a step after after_step (dict as reading); "
          "Timeout")
      .def(
          "image",
          [](Sim& s, const std::string& name, bool depth) -> py::object {
            const auto image = s.client().LatestImage(name, ImageKindOf(depth));
            if (!image) return py::none();
            return ImageDict(std::move(*image));
          },
          py::arg("name"), py::arg("depth") = false,
          "The newest image of camera `name` (rendered by simpartner-camera), or None before "
          "the first; the first call starts receiving images (so it returns None). Dict as "
          "wait_image's.")
      .def(
          "wait_image",
          [](Sim& s, const std::string& name, int64_t after_step, double timeout, bool depth) {
            simpartner::image_t image;
            {
              py::gil_scoped_release release;
              image = s.client().WaitForImage(name, after_step, timeout, ImageKindOf(depth));
            }
            return ImageDict(std::move(image));
          },
          py::arg("name"), py::arg("after_step") = -1, py::arg("timeout") = 2.0,
          py::arg("depth") = false,
          "Waits for an image of camera `name` showing a step after after_step; Timeout. Dict "
          "of name, robot, step, time [s of sim time], width, height, format ('rgb8', "
          "'depth-f32', 'depth-u16') and pixels: depth=False, the colour image, uint8 of shape "
          "(height, width, 3), RGB, row 0 at the top; depth=True, the depth along the camera's "
          "axis, shape (height, width): float32 metres (+inf: nothing before far) for "
          "'depth-f32', uint16 millimetres (0: nothing, or beyond 65.535 m) for 'depth-u16', as "
          "the camera declares.")
      .def(
          "lockstep",
          [](Sim& s, int64_t period, std::optional<int64_t> steps, const std::string& name,
             bool resume, double timeout) {
            return std::make_unique<LockStepLoop>(s, period, steps, name, resume, timeout);
          },
          py::arg("period") = 1, py::arg("steps") = py::none(), py::arg("name") = "",
          py::arg("resume") = true, py::arg("timeout") = 10.0, py::keep_alive<0, 1>(),
          "for state in sim.lockstep(period=1, steps=N): joins the sim as a synchronous "
          "controller (resuming it if paused) and yields the state of every period-th step; the "
          "commands given in the loop body (set_velocity, set_angle, hold) apply in the next "
          "step, so a closed loop repeats bit for bit at any speed. Leaves when the loop ends. "
          "LockStepError when the sim refuses or releases it, Refused at the tick after a refused "
          "command.")
      .def("wait_until", &Sim::WaitUntil, py::arg("sim_time"), py::arg("timeout") = 10.0,
           "Waits for a state at sim_time or later and returns it; Timeout")
      .def(
          "set_velocity",
          [](Sim& s, const std::string& name, std::vector<double> velocity, double max_force,
             double timeout) {
            const client::Target t = s.client().Find(name);
            return s.Send(client::SetVelocity(t, velocity, max_force), timeout);
          },
          py::arg("name"), py::arg("velocity"), py::arg("max_force") = client::kDefaultMaxForce,
          py::arg("timeout") = -1.0, "Velocity per axis; returns the step it was applied at")
      .def(
          "set_angle",
          [](Sim& s, const std::string& name, std::vector<double> angle, double p, double i,
             double d, double max_force, double timeout) {
            const client::Target t = s.client().Find(name);
            return s.Send(client::SetAngle(t, angle, p, i, d, max_force), timeout);
          },
          py::arg("name"), py::arg("angle"), py::arg("p") = 5.0, py::arg("i") = 0.0,
          py::arg("d") = 0.0, py::arg("max_force") = client::kDefaultMaxForce,
          py::arg("timeout") = -1.0)
      .def(
          "hold",
          [](Sim& s, const std::string& name, double max_force, double timeout) {
            const client::Target t = s.client().Find(name);
            return s.Send(client::Hold(t, max_force), timeout);
          },
          py::arg("name"), py::arg("max_force") = client::kDefaultMaxForce, py::arg("timeout") = -1.0)
      .def(
          "command",
          [](Sim& s, const std::string& name, const std::string& values, const std::string& action,
             double timeout) {
            int code = -1;
            for (const simpartner::ActionSpelling& a : simpartner::ActionSpellings())
              if (action == a.word) code = a.action;
            if (code < 0)
              throw py::value_error("action '" + action +
                                    "' is not one of set, hold, stops, params, read");
            const client::Target t = s.client().Find(name);
            return s.Send(client::BuildCommandFromText(t, code, values), timeout);
          },
          py::arg("name"), py::arg("values") = "", py::arg("action") = "set",
          py::arg("timeout") = -1.0,
          "Any command, as simpartner-cmd takes it: action set, hold, stops, params or read, "
          "values as the original's text ('1000,0.5'); returns the step it applies in")
      .def("pause", [](Sim& s) { s.client().Pause(); })
      .def("resume", [](Sim& s) { s.client().Resume(); })
      .def("step", [](Sim& s, int64_t steps) { s.client().Step(steps); }, py::arg("steps") = 1)
      .def("set_speed", [](Sim& s, double factor) { s.client().SetSpeed(factor); },
           py::arg("real_time_factor"))
      .def(
          "reset",
          [](Sim& s, double timeout) {
            py::gil_scoped_release release;
            s.client().Reset(timeout);
          },
          py::arg("timeout") = 3.0, "Resets the sim and learns its new model")
      .def(
          "status",
          [](Sim& s) -> py::object {
            const auto st = s.client().LatestStatus();
            if (!st) return py::none();
            static const char* kStates[] = {"running", "paused", "stopped", "faulted", "reset"};
            py::dict d;
            d["step"] = st->step;
            d["time"] = st->sim_time;
            d["state"] = st->run_state >= 0 && st->run_state < 5 ? kStates[st->run_state] : "unknown";
            d["real_time_factor"] = st->real_time_factor;
            return d;
          });

  py::class_<LockStepLoop>(m, "LockStep", "The iterator sim.lockstep() returns.")
      .def("__iter__", [](LockStepLoop& l) -> LockStepLoop& { return l; })
      .def("__next__", &LockStepLoop::Next)
      .def("__enter__", [](LockStepLoop& l) -> LockStepLoop& { return l; })
      .def("__exit__", [](LockStepLoop& l, py::args) { l.Close(); })
      .def("close", &LockStepLoop::Close, "Leaves lock-step (the sim stops waiting for it)")
      .def_property_readonly("tick", &LockStepLoop::tick, "The tick of the last state, -1 before");

  m.def("read_logged", &ReadLogged, py::arg("simulation") = "last", py::arg("db_options") = "",
        py::arg("dbname") = "simpartner", py::arg("dbserver") = "", py::arg("velocities") = false,
        py::arg("start") = py::none(), py::arg("end") = py::none(), py::arg("bodies") = py::none(),
        py::arg("joints") = py::none(), py::arg("forces") = false,
        "A logged simulation from the database: dict with time (n,), step (n,), bodies "
        "{name: (n, 7 or 10)}, joints {name: (n, 15), angles continuous}, forces {name: (n, 6)} "
        "(with forces=True), body_columns, joint_columns, force_columns, simulation (its id), "
        "engine ('ode' or 'mujoco'). "
        "simulation: an id (int), 'last' or 'running'. start, end: only the steps from start to "
        "end [s of sim time] (None: from the first, to the last). bodies, joints: None (all), a "
        "name or a list of names ([] for none). velocities: add vx, vy, vz (central differences). "
        "db_options: client option file (default: reader.cnf of the private server of "
        "simpartner-mariadb, in $SIMPARTNER_STATE/mariadb, ./state/mariadb or "
        "~/.local/state/simpartner/mariadb).");
}
