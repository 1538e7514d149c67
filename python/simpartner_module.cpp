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

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/client/client.h"
#include "simpartner/client/command.h"
#include "simpartner/logger/query.h"
#include "simpartner/parameters.h"

namespace py = pybind11;

namespace {

using simpartner::client::Client;
using simpartner::client::ClientOptions;

// An (rows, columns) float64 array.
py::array_t<double> Matrix(size_t rows, size_t columns) {
  return py::array_t<double>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(columns)});
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

  py::object State() const {
    const std::optional<simpartner::state_t> s = client_->LatestState();
    if (!s) return py::none();
    return StateDict(*s);
  }

  py::dict WaitUntil(double sim_time, double timeout) {
    simpartner::state_t s;
    {
      py::gil_scoped_release release;
      s = client_->WaitUntilSimTime(sim_time, timeout);
    }
    return StateDict(s);
  }

  int64_t Send(const simpartner::command_t& command, double timeout) {
    simpartner::command_reply_t reply;
    py::gil_scoped_release release;
    reply = client_->Command(command, timeout);
    return reply.applied_at_step;
  }

 private:
  std::unique_ptr<Client> client_;
};

// The logged simulation `simulation` of the database: per body and joint
// arrays over the logged steps.
py::dict ReadLogged(const std::string& simulation, const std::string& db_options,
                    const std::string& dbname, const std::string& dbserver, bool velocities) {
  using namespace simpartner::logger;
  simpartner::Parameters params;
  std::vector<std::string> warnings;
  params.dbname = dbname;
  params.dbserver = dbserver;
  const DbTarget target = ResolveDbTarget(params, db_options, kPrivateReaderOptions, &warnings);
  std::unique_ptr<DbConnection> db = DbConnection::Open(target, false);
  db->UseDatabase(false);

  py::dict result;
  std::vector<double> times;
  // name -> flat values per step
  std::map<std::string, std::vector<double>> pose, joint;
  std::vector<std::string> body_order, joint_order;
  ExportRequest poses;
  poses.simulation = simulation;
  poses.velocities = velocities;
  uint32_t id = 0;
  {
    py::gil_scoped_release release;
    id = ReadExport(db.get(), poses, [&](const ExportStep& step) {
      times.push_back(step.time);
      for (const ExportRow& row : step.rows) {
        auto [it, fresh] = pose.try_emplace(row.name);
        if (fresh) body_order.push_back(row.name);
        it->second.insert(it->second.end(), row.values.begin(), row.values.end());
      }
    });
    ExportRequest joints;
    joints.kind = ExportKind::kJoints;
    joints.simulation = std::to_string(id);
    joints.unwrap = true;
    ReadExport(db.get(), joints, [&](const ExportStep& step) {
      for (const ExportRow& row : step.rows) {
        auto [it, fresh] = joint.try_emplace(row.name);
        if (fresh) joint_order.push_back(row.name);
        it->second.insert(it->second.end(), row.values.begin(), row.values.end());
      }
    });
  }
  DbThreadEnd();
  const size_t steps = times.size();
  const size_t pose_columns = velocities ? 10 : 7;
  auto as_matrix = [](const std::vector<double>& flat, size_t columns) {
    const size_t rows = columns ? flat.size() / columns : 0;
    auto m = Matrix(rows, columns);
    std::copy(flat.begin(), flat.begin() + static_cast<std::ptrdiff_t>(rows * columns), m.mutable_data());
    return m;
  };
  result["simulation"] = id;
  result["time"] = py::array_t<double>(static_cast<py::ssize_t>(steps), times.data());
  py::dict bodies, joints_out;
  for (const std::string& name : body_order) bodies[py::str(name)] = as_matrix(pose[name], pose_columns);
  for (const std::string& name : joint_order) joints_out[py::str(name)] = as_matrix(joint[name], 15);
  result["bodies"] = bodies;
  result["joints"] = joints_out;
  result["body_columns"] = ExportColumns(poses);
  ExportRequest j;
  j.kind = ExportKind::kJoints;
  result["joint_columns"] = ExportColumns(j);
  return result;
}

}  // namespace

PYBIND11_MODULE(simpartner, m) {
  m.doc() = "SimPartner: drive a running simpartner-sim over LCM and read logged simulations";
  namespace client = simpartner::client;
  auto client_error = py::register_exception<client::ClientError>(m, "ClientError", PyExc_RuntimeError);
  // The subclasses: registered after the base so that each maps to its own.
  py::register_exception<client::UnknownTarget>(m, "UnknownTarget", client_error.ptr());
  py::register_exception<client::Refused>(m, "Refused", client_error.ptr());
  py::register_exception<client::Timeout>(m, "Timeout", client_error.ptr());
  py::register_exception<client::NoSim>(m, "NoSim", client_error.ptr());
  py::register_exception<client::SimRestarted>(m, "SimRestarted", client_error.ptr());
  py::register_exception<client::BadValues>(m, "BadValues", client_error.ptr());
  py::register_exception<simpartner::Error>(m, "DatabaseError", PyExc_RuntimeError);
  m.attr("DEFAULT_URL") = client::kDefaultUrl;

  py::class_<Sim>(m, "Sim", "A connection to the sim on the bus (the client library's Client).")
      .def(py::init<const std::string&, double, const std::string&>(), py::arg("url") = client::kDefaultUrl,
           py::arg("timeout") = 3.0, py::arg("program") = "python",
           "Connects and learns the model; NoSim when no sim answers within timeout s.")
      .def_property_readonly("url", [](Sim& s) { return s.client().url(); })
      .def("model", &Sim::Model, "dict: simulation_id, world, step_size, robots, bodies, joints, "
                                 "targets (name, robot, kind, type, joint, axes)")
      .def("state", &Sim::State, "The newest state (dict of NumPy arrays), or None before the first")
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
            static const char* kStates[] = {"running", "paused", "stopped", "faulted"};
            py::dict d;
            d["step"] = st->step;
            d["time"] = st->sim_time;
            d["state"] = st->run_state >= 0 && st->run_state < 4 ? kStates[st->run_state] : "unknown";
            d["real_time_factor"] = st->real_time_factor;
            return d;
          });

  m.def("read_logged", &ReadLogged, py::arg("simulation") = "last", py::arg("db_options") = "",
        py::arg("dbname") = "simpartner", py::arg("dbserver") = "", py::arg("velocities") = false,
        "A logged simulation from the database: dict with time (n,), bodies {name: (n, 7 or 10)}, "
        "joints {name: (n, 15), angles unwrapped}, body_columns, joint_columns. simulation: an id, "
        "'last' or 'running'. db_options: client option file (default: reader.cnf of the "
        "private server of simpartner-mariadb, in $SIMPARTNER_STATE/mariadb, ./state/mariadb or "
        "~/.local/state/simpartner/mariadb).");
}
