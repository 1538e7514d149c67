#include "simpartner/client/cmd.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "simpartner/bus_signing.h"
#include "simpartner/client/client.h"
#include "simpartner/client/image_summary.h"
#include "simpartner/command_line.h"
#include "simpartner/diagnostic.h"
#include "simpartner/command_t.hpp"
#include "simpartner/sensor_t.hpp"
#include "simpartner/sim_engine.h"
#include "simpartner/status_t.hpp"
#include "simpartner/text.h"

namespace simpartner::client {
namespace {

using Clock = std::chrono::steady_clock;

struct UsageError : ClientError {
  using ClientError::ClientError;
};

std::string Join(const std::vector<double>& values) {
  std::string out;
  for (size_t k = 0; k < values.size(); ++k) out += (k ? "," : "") + FormatNumber(values[k]);
  return out;
}

const char* RunStateName(int run_state) {
  switch (run_state) {
    case status_t::RUN_RUNNING: return "running";
    case status_t::RUN_PAUSED: return "paused";
    case status_t::RUN_STOPPED: return "stopped";
    case status_t::RUN_FAULTED: return "faulted (paused by the health check)";
    case status_t::RUN_RESET: return "reset (its successor follows)";
    default: return "unknown";
  }
}

bool SameWarning(const warning_t& a, const warning_t& b) {
  return a.step == b.step && a.source == b.source && a.message == b.message;
}

// A status line and its warnings. Those already in `seen` (a status printed
// or read before) are not repeated, since the sim keeps its recent warnings
// in every status; with count_seen a line says how many were left out.
std::string FormatStatus(const status_t& s, const status_t* seen = nullptr,
                         bool count_seen = false) {
  std::ostringstream out;
  out << RunStateName(s.run_state) << ", step " << s.step << ", t = " << FormatNumber(s.sim_time)
      << " s, " << FormatNumber(s.real_time_factor) << "x real time (target "
      << (s.target_speed <= 0 ? std::string("as fast as possible") : FormatNumber(s.target_speed) + "x")
      << "), simulation " << s.simulation_id << " on " << s.host << ", engine "
      << SimEngine(s.engine) << ", commands "
      << s.commands_accepted << " accepted / " << s.commands_rejected << " refused, "
      << s.bad_messages << " bad messages";
  size_t repeated = 0;
  for (const warning_t& w : s.warnings) {
    const bool old = seen != nullptr &&
                     std::any_of(seen->warnings.begin(), seen->warnings.end(),
                                 [&w](const warning_t& v) { return SameWarning(v, w); });
    if (old) ++repeated;
    else out << "\n  step " << w.step << " " << w.source << ": " << w.message;
  }
  if (count_seen && repeated > 0)
    out << "\n  (" << repeated << " earlier warning" << (repeated == 1 ? "" : "s")
        << " not repeated: simpartner-cmd status lists them)";
  return out.str();
}

std::string FormatBody(const std::string& name, const body_state_t& b) {
  std::ostringstream out;
  out << name << " position " << FormatNumber(b.position[0]) << "," << FormatNumber(b.position[1]) << ","
      << FormatNumber(b.position[2]) << " orientation " << FormatNumber(b.orientation[0]) << ","
      << FormatNumber(b.orientation[1]) << "," << FormatNumber(b.orientation[2]) << "," << FormatNumber(b.orientation[3])
      << " velocity " << FormatNumber(b.linear_velocity[0]) << "," << FormatNumber(b.linear_velocity[1]) << ","
      << FormatNumber(b.linear_velocity[2]);
  return out.str();
}

std::string FormatState(const state_t& s, const Catalog& catalog, int body) {
  std::ostringstream out;
  out << "step " << s.step << ", t = " << FormatNumber(s.sim_time) << " s";
  const auto& names = catalog.body_names();
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    if (body >= 0 && static_cast<int>(i) != body) continue;
    out << "\n  " << FormatBody(i < names.size() ? names[i] : "body " + std::to_string(i),
                               s.bodies[i]);
  }
  if (body < 0) {
    const auto& joints = catalog.joint_names();
    for (size_t j = 0; j < s.joints.size() && j < joints.size(); ++j)
      out << "\n  joint " << joints[j] << " position " << FormatNumber(s.joints[j].position[0]) << ","
          << FormatNumber(s.joints[j].position[1]) << " rate " << FormatNumber(s.joints[j].rate[0]) << ","
          << FormatNumber(s.joints[j].rate[1]);
  }
  return out.str();
}

// Waits for a SIM_STATUS sent after the call that satisfies `done`.
std::optional<status_t> AwaitStatus(Client& client, double timeout,
                                    const std::function<bool(const status_t&)>& done) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0) return std::nullopt;
    try {
      status_t s = client.WaitForStatus(left);
      if (done(s)) return s;
    } catch (const Timeout&) {
      return std::nullopt;
    }
  }
}

// The image of read --out could not be written (the writer's reason).
class ImageFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string url;                 // --lcm-url, else lcmUrl of the parameters
  double timeout = 2.0;
  std::vector<std::string> words;  // command and its arguments
  std::string body;
  bool follow = false;
  bool depth = false;  // read CAMERA: the depth image
  std::string image_file;  // read CAMERA --out: where to write the image
  long count = -1;  // --follow: stop after this many (tests), -1 = forever
  int64_t simulation_id = 0;  // --sim: the simulation to talk to; 0 = the first heard
};

double ParseNumber(const std::string& what, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw UsageError(what + " '" + text + "' is not a number");
  return v;
}

// The command line, checked by ParseCommandLine, and the bus of the
// parameters the other programs read (--lcm-url is --lcmUrl=URL).
Options MakeOptions(const CommandLine& command_line, const Parameters& params) {
  Options o;
  o.url = params.lcmUrl;
  o.timeout = command_line.Number("timeout", o.timeout);
  o.words = command_line.positional();
  o.words.insert(o.words.begin(), command_line.command());
  o.body = command_line.Text("body");
  o.follow = command_line.Has("follow");
  o.depth = command_line.Has("depth");
  o.image_file = command_line.Text("out");
  o.count = static_cast<long>(command_line.Integer("count", o.count));
  o.simulation_id = command_line.Integer("sim", o.simulation_id);
  return o;
}

ClientOptions MakeClientOptions(const Options& o, bool learn_model) {
  ClientOptions c;
  c.url = o.url;
  c.program = "simpartner-cmd";
  c.model_timeout = o.timeout;
  c.reply_timeout = o.timeout;
  c.learn_model = learn_model;
  c.simulation_id = o.simulation_id;
  return c;
}

// A command that waits for its reply; a paused sim answers only when it
// steps, which the timeout message says.
command_reply_t SendAndWait(Client& client, const command_t& command, double timeout) {
  try {
    return client.Command(command, timeout);
  } catch (const Timeout& e) {
    // Why no reply? A paused sim says so in its status (once a second).
    std::optional<status_t> status = client.LatestStatus();
    if (!status) {
      try {
        status = client.WaitForStatus(1.5);
      } catch (const Timeout&) {
      }
    }
    if (status && status->run_state != status_t::RUN_RUNNING)
      throw Timeout(e.awaited(), timeout, client.url(),
                    std::string("the sim is ") + RunStateName(status->run_state) +
                        ": it applies and answers commands when it steps");
    throw;
  }
}

int RunActuatorCommand(const Options& o, std::ostream& out) {
  const std::string& verb = o.words[0];
  Client client(MakeClientOptions(o, true));
  const Target target = client.Find(o.words[1]);
  command_t command;
  if (verb == "set") {
    // A sensor's "set" is its parameters, but an Echo sensor takes text.
    const bool params = target.is_sensor() && target.lcm_kind != sensor_t::KIND_ECHO;
    command = BuildCommandFromText(
        target, params ? command_t::ACTION_SENSOR_PARAMS : command_t::ACTION_SET, o.words[2]);
  } else if (verb == "hold") {
    if (o.words.size() == 3) {
      const std::vector<double> given = ParseValueText(target.name, o.words[2]);
      std::vector<double> forces = given;
      if (given.size() == 1 && target.num_axes > 1)
        forces.assign(static_cast<size_t>(target.num_axes), given[0]);
      command = BuildCommand(target, command_t::ACTION_HOLD, forces);
    } else {
      command = BuildCommand(target, command_t::ACTION_HOLD, {});
    }
  } else {  // stops
    command = BuildCommandFromText(target, command_t::ACTION_SET_STOPS, o.words[2]);
  }
  const command_reply_t reply = SendAndWait(client, command, o.timeout);
  out << reply.target << ": accepted, applied at step " << reply.applied_at_step;
  if (!reply.previous_text.empty()) out << " (was " << reply.previous_text << ")";
  out << "\n";
  return kCmdOk;
}

// A camera has no SIM_SENSOR reading: the next image simpartner-camera
// renders of it (colour, or with --depth its depth image).
int RunReadCamera(Client& client, const Target& target, const Options& o, std::ostream& out,
                  const ImageFileWriter& write_image) {
  if (!o.image_file.empty() && !write_image)
    throw UsageError("--out: this program writes no image files");
  const ImageKind kind = o.depth ? ImageKind::kDepth : ImageKind::kColour;
  client.LatestImage(target.qualified_name(), kind);  // starts receiving images
  const image_t image = client.WaitForImage(target.qualified_name(), -1, o.timeout, kind);
  out << target.name << " (camera) step " << image.step << ", t = " << FormatNumber(image.sim_time)
      << " s: " << SummariseImage(image) << "\n";
  if (o.image_file.empty()) return kCmdOk;
  try {
    write_image(o.image_file, image);
  } catch (const std::exception& e) {
    throw ImageFileError(e.what());
  }
  out << "written to " << o.image_file
      << (o.depth ? " (16-bit grey, millimetres)\n" : " (RGB)\n");
  return kCmdOk;
}

int RunRead(const Options& o, std::ostream& out, const ImageFileWriter& write_image) {
  Client client(MakeClientOptions(o, true));
  const Target target = client.Find(o.words[1]);
  if (!target.is_sensor())
    throw UnknownTarget(o.words[1], {}, "'" + o.words[1] + "' is an actuator; read takes a sensor");
  if (target.lcm_kind == sensor_t::KIND_CAMERA)
    return RunReadCamera(client, target, o, out, write_image);
  if (!o.image_file.empty())
    throw UsageError("--out is for a camera, and '" + o.words[1] + "' is not one (" +
                     target.kind_name() + ")");
  if (o.depth)
    throw UsageError("--depth is for a camera, and '" + o.words[1] + "' is not one (" +
                     target.kind_name() + ")");
  const command_reply_t reply = SendAndWait(client, Read(target), o.timeout);
  const sensor_reading_t r =
      client.WaitForReading(target.qualified_name(), reply.applied_at_step - 1, o.timeout);
  out << target.name << " (" << target.kind_name() << ") step " << r.step << ", t = "
      << FormatNumber(r.sim_time) << " s: ";
  if (!r.text.empty() || r.values.empty()) out << "'" << r.text << "'";
  else out << Join(r.values);
  out << "\n";
  return kCmdOk;
}

// The key file this program signs with (the user's, made now when it was
// missing), checked, or "none": what another machine needs a copy of
// (docs/several-machines.md).
int RunKey(std::ostream& out, std::ostream& err) {
  try {
    const std::string path = ChooseBusKeyFile(
        [&err](const std::string& line) { err << "simpartner-cmd: " << line << "\n"; });
    if (!path.empty()) BusSigning::LoadKey(path);
    out << (path.empty() ? std::string(kNoBusKey) : path) << "\n";
  } catch (const BusKeyError& e) {
    throw ClientError(e.what());
  }
  return kCmdOk;
}

int RunControl(const Options& o, std::ostream& out) {
  const std::string& verb = o.words[0];
  Client client(MakeClientOptions(o, false));
  // A first status tells that a sim is there and where it is; the client
  // is then attached to it (or to --sim), and the control carries its id:
  // another sim on the bus ignores it.
  std::optional<status_t> before = AwaitStatus(client, o.timeout, [&o](const status_t& s) {
    return o.simulation_id == 0 || s.simulation_id == o.simulation_id;
  });
  if (!before && o.simulation_id != 0)
    throw Timeout("SIM_STATUS of simulation " + std::to_string(o.simulation_id), o.timeout, o.url,
                  client.SigningHint());
  if (!before)
    throw NoSim(o.url, o.timeout, client.SigningHint());
  std::function<bool(const status_t&)> done;
  std::string what;
  if (verb == "pause") {
    client.Pause();
    done = [](const status_t& s) { return s.run_state == status_t::RUN_PAUSED; };
  } else if (verb == "resume") {
    client.Resume();
    done = [](const status_t& s) { return s.run_state == status_t::RUN_RUNNING; };
  } else if (verb == "step") {
    const double n = ParseNumber("step count", o.words[1]);
    if (n < 1 || n > 1e8 || n != std::floor(n))
      throw UsageError("step count '" + o.words[1] + "' must be a whole number from 1 to 100000000");
    const int64_t target_step = before->step + static_cast<int64_t>(n);
    client.Step(static_cast<int64_t>(n));
    // Done when the sim stands paused at or past the step it was sent to.
    done = [target_step](const status_t& s) {
      return s.run_state == status_t::RUN_PAUSED && s.step >= target_step;
    };
  } else if (verb == "speed") {
    const double speed = ParseNumber("speed", o.words[1]);
    client.SetSpeed(speed);
    done = [speed](const status_t& s) {
      return speed <= 0 ? s.target_speed <= 0 : std::abs(s.target_speed - speed) < 1e-9;
    };
  } else {  // quit
    client.Quit();
    done = [](const status_t& s) { return s.run_state == status_t::RUN_STOPPED; };
  }
  // The answer may have come before the wait began: a quit's RUN_STOPPED
  // comes once, and a paused sim answers at once.
  std::optional<status_t> after = client.LatestStatus();
  if (!after || !done(*after)) after = AwaitStatus(client, o.timeout, done);
  if (!after)
    throw Timeout("SIM_STATUS confirming '" + verb + "'", o.timeout, o.url, client.SigningHint());
  out << "sim " << FormatStatus(*after, &*before, true) << "\n";
  return kCmdOk;
}

int RunReset(const Options& o, std::ostream& out) {
  Client client(MakeClientOptions(o, true));
  const auto catalog = client.Reset(o.timeout);
  out << "sim reset: simulation " << catalog->simulation_id() << "\n";
  return kCmdOk;
}

int RunModel(const Options& o, std::ostream& out) {
  Client client(MakeClientOptions(o, true));
  out << client.catalog()->Describe();
  return kCmdOk;
}

int RunState(const Options& o, std::ostream& out) {
  Client client(MakeClientOptions(o, true));
  auto catalog = client.catalog();
  int body = o.body.empty() ? -1 : catalog->BodyIndex(o.body);
  if (!o.follow && o.count < 0) {
    // The state now, running or paused (a paused sim sends no SIM_STATE).
    out << FormatState(client.RequestState(o.timeout), *catalog, body) << "\n";
    return kCmdOk;
  }
  int64_t last_step = -1;
  long printed = 0;
  do {
    // The next state after the last one printed (the newest, when not following).
    const auto current = client.LatestState();
    const double step_time = catalog->step_size() * catalog->state_every();
    const double wait_until =
        current ? current->sim_time + (last_step < 0 ? 0.0 : step_time) : 0.0;
    state_t s;
    try {
      s = client.WaitUntilSimTime(wait_until, o.timeout);
    } catch (const Timeout&) {
      // Following a paused sim: go on while it is heard (its status).
      if (o.follow && printed > 0 && client.SecondsSinceHeard() < o.timeout) continue;
      throw;
    } catch (const SimRestarted& e) {
      if (!o.follow) throw;
      catalog = client.Relearn(o.timeout);
      body = o.body.empty() ? -1 : catalog->BodyIndex(o.body);
      out << e.what() << "; following simulation " << catalog->simulation_id() << "\n";
      last_step = -1;
      continue;
    }
    if (s.step == last_step) continue;
    last_step = s.step;
    out << FormatState(s, *catalog, body) << "\n" << std::flush;
    ++printed;
  } while (o.follow && (o.count < 0 || printed < o.count));
  return kCmdOk;
}

int RunStatus(const Options& o, std::ostream& out) {
  Client client(MakeClientOptions(o, false));
  long printed = 0;
  std::optional<status_t> previous;  // following: each warning once
  do {
    const auto s = AwaitStatus(client, o.timeout, [](const status_t&) { return true; });
    if (!s) throw Timeout("SIM_STATUS", o.timeout, o.url, client.SigningHint());
    out << FormatStatus(*s, previous ? &*previous : nullptr) << "\n" << std::flush;
    previous = s;
    ++printed;
  } while (o.follow && (o.count < 0 || printed < o.count));
  return kCmdOk;
}

}  // namespace

CommandLineSpec CmdCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-cmd";
  spec.summary = "Talks to a running simpartner-sim on the LCM bus.";
  spec.options = {
      Number("timeout", "S", "seconds to wait for the sim's answer (default 2)").Above(0, 3600),
      Text("body", "NAME", "only this body"),
      Switch("follow", "every one until interrupted, not only the newest"),
      Switch("depth", "a camera's depth image, not its colour image"),
      Text("out", "FILE", "read CAMERA: also write the image to FILE (PNG; depth as 16-bit mm)"),
      Integer("count", "N", "with --follow: stop after N"),
      Integer("sim", "ID", "talk to the simulation of this id only (several sims on one bus); "
                           "default: the first sim heard")
          .Above(0),
  };
  const Positional name{"NAME"};
  spec.commands = {
      {"set", {name, Positional{"VALUES"}},
       "set an actuator, e.g. set Axle1Motor 1000,1000,100,0,0,0.2\n"
       "or per axis: set Axle1Motor 300,1.0 (fmax, velocity);\n"
       "a sensor: its parameters (rate, or rate,rays,halfSpan,range)"},
      {"hold", {name, Positional{"FMAX", 0, 1}},
       "hold the joint where it is (force limit per axis, default 1000)"},
      {"stops", {name, Positional{"LO1,HI1,..."}}, "joint stops (per slot x,y,z or per axis)"},
      {"read", {Positional{"SENSOR"}},
       "ask a sensor for a reading and print it; a camera:\n"
       "its next image's size, mean colour or depth range",
       {"depth", "out"}},
      {"pause", {}, "pause the sim"},
      {"resume", {}, "resume a paused sim"},
      {"step", {Positional{"N"}}, "take N steps, then stay paused"},
      {"speed", {Positional{"X"}}, "real-time factor; 0 = as fast as possible"},
      {"reset", {}, "start the simulation again from the world's initial state"},
      {"quit", {}, "end the sim"},
      {"model", {}, "robots, actuators (kind, port, value forms), sensors"},
      {"state", {}, "newest SIM_STATE (or every one)", {"body", "follow", "count"}},
      {"status", {}, "newest SIM_STATUS (or every one)", {"follow", "count"}},
      {"key", {}, "the bus key file this program signs with (the user's is made when\n"
                  "missing), or 'none'; copy it to share the bus (docs/several-machines.md)"},
  };
  spec.parameters = ParameterUse{{parameter_sections::kTransport}};
  spec.epilogue =
      "NAME is a name from 'model', robot/name, or a legacy port (1028).\n"
      "Exit status: 0 accepted, 1 refused by the sim, 2 usage error, 3 no answer,\n"
      "             4 unknown name, 5 the sim restarted.";
  return spec;
}

int RunCmd(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
           const ImageFileWriter& write_image) {
  const char* prefix = "simpartner-cmd: ";
  const CommandLineSpec spec = CmdCommandLine();
  CommandLine command_line;
  if (const auto done = ReadCommandLine(spec, args, out, err, &command_line)) return *done;
  try {
    const Parameters params = LoadParameters(command_line.parameter_sources());
    if (PrintParametersIfAsked(command_line, params, out)) return kCmdOk;
    const Options o = MakeOptions(command_line, params);
    const std::string& verb = o.words[0];
    if (verb == "set" || verb == "hold" || verb == "stops") return RunActuatorCommand(o, out);
    if (verb == "read") return RunRead(o, out, write_image);
    if (verb == "reset") return RunReset(o, out);
    if (verb == "model") return RunModel(o, out);
    if (verb == "state") return RunState(o, out);
    if (verb == "status") return RunStatus(o, out);
    if (verb == "key") return RunKey(out, err);
    return RunControl(o, out);  // pause, resume, step, speed, quit
  } catch (const UsageError& e) {
    return ReportUsageError(spec, e.what(), err);
  } catch (const BadValues& e) {
    err << prefix << e.what() << "\n";
    return kCmdUsage;
  } catch (const Refused& e) {
    err << prefix << e.what() << "\n";
    return kCmdRefused;
  } catch (const UnknownTarget& e) {
    err << prefix << e.what() << "\n";
    return kCmdUnknownName;
  } catch (const NoSim& e) {
    err << prefix << e.what() << "\n";
    return kCmdNoAnswer;
  } catch (const Timeout& e) {
    err << prefix << e.what() << "\n";
    return kCmdNoAnswer;
  } catch (const SimRestarted& e) {
    err << prefix << e.what() << "\n";
    return kCmdRestarted;
  } catch (const ImageFileError& e) {
    err << prefix << e.what() << "\n";
    return kCmdFileError;
  } catch (const ClientError& e) {
    err << prefix << e.what() << "\n";
    return kCmdUsage;
  } catch (const DiagnosticError& e) {  // the parameters file
    err << e.diagnostics().Format() << "\n" << prefix << "bad parameters; nothing sent\n";
    return kCmdUsage;
  }
}

}  // namespace simpartner::client
