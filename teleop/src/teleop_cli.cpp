#include "simpartner/teleop/teleop_cli.h"

#include <cmath>
#include <ostream>

#include "simpartner/client/errors.h"
#include "simpartner/data_paths.h"

namespace simpartner::teleop {
namespace {

// The shipped mappings: found like every data file (data_paths.h); a name
// that is nowhere still goes into --help, and --check reports it missing.
std::string DefaultMappingDir() {
  try {
    return FindDataDirectory("teleop/mappings", "mapping directory");
  } catch (const DataFileNotFound&) {
    return "teleop/mappings";
  }
}

}  // namespace

CommandLineSpec TeleopCommandLine(bool virtual_pad) {
  CommandLineSpec spec;
  spec.program = virtual_pad ? "simpartner-teleop-vpad" : "simpartner-teleop";
  spec.summary =
      "Drives the robot of the sim on the bus from the first game controller (hot-plug), or "
      "with --input keyboard from a small window (arrows or WASD). Hold the dead-man button "
      "(keyboard: space) to move.";
  if (virtual_pad)
    spec.summary +=
        "\n\nsimpartner-teleop-vpad: a virtual game controller stands in for a real one, driven "
        "by the lines of a script (--script FILE, default stdin): 'axis <name> <-1..1>', "
        "'button <name> <0|1>', detach, attach, quit; for scripted teleop without a controller "
        "and for the process tests (docs/driving.md).";
  spec.options = {
      Text("lcm-url", "URL", std::string("the bus (default ") + client::kDefaultUrl + ")"),
      Text("input", "gamepad|keyboard",
           "a game controller (default) or the keyboard window")
          .Choices({"gamepad", "keyboard"}),
      Text("mapping", "FILE", "mapping file (default: the shipped one for the robot's model)"),
      Text("mapping-dir", "DIR", "where the shipped mappings are (default: " + DefaultMappingDir() + ")"),
      Number("max-speed", "R", "wheel speed at full stick [rad/s] (overrides the mapping)").Above(0),
      Number("max-steer", "A", "Turner angle at full stick [rad] (overrides the mapping)").Above(0),
      Switch("list", "name the connected game controllers and exit"),
      Switch("check", "check the mapping against the robot of --environment WORLD, offline"),
      Text("environment", "WORLD", "the world --check checks against"),
  };
  if (virtual_pad)
    spec.options.push_back(Text("script", "FILE", "the pad's script (default: stdin)"));
  return spec;
}

TeleopOptions MakeTeleopOptions(const CommandLine& command_line, bool virtual_pad) {
  TeleopOptions o;
  o.session.program = virtual_pad ? "teleop-vpad" : "teleop";
  o.session.url = command_line.Text("lcm-url", o.session.url);
  o.session.mapping_file = command_line.Text("mapping");
  o.session.mapping_dir = command_line.Text("mapping-dir", DefaultMappingDir());
  o.session.max_speed = command_line.Number("max-speed", NAN);
  o.session.max_steer = command_line.Number("max-steer", NAN);
  o.input = command_line.Text("input") == "keyboard" ? TeleopInput::kKeyboard : TeleopInput::kGamepad;
  o.list = command_line.Has("list");
  o.check = command_line.Has("check");
  o.environment = command_line.Text("environment");
  if (virtual_pad) o.script = command_line.Text("script");
  return o;
}

int CheckMapping(const TeleopOptions& options, std::ostream& out, std::ostream& err) {
  const std::string& environment = options.environment;
  try {
    const model_t model = ModelFromWorldFile(environment);
    if (model.robots.empty()) {
      err << environment << ": the world has no robot\n";
      return 1;
    }
    const std::string file = options.session.mapping_file.empty()
                                 ? MappingFileFor(model.robots[0].model, options.session.mapping_dir)
                                 : options.session.mapping_file;
    const Plan plan = BuildPlan(LoadMapping(file), model);
    out << file << ": fits robot " << plan.robot << " (" << model.robots[0].model << ") of "
        << environment << ": " << plan.wheels.size() << " wheels (signs";
    for (const Plan::Wheel& w : plan.wheels) out << " " << w.target.name << (w.sign > 0 ? " +" : " -");
    out << ")" << (plan.steer ? ", steering " + plan.steer->target.name : std::string()) << ", "
        << plan.levels.size() << " levels\n";
    return 0;
  } catch (const MappingError& e) {
    err << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    err << "simpartner-teleop: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace simpartner::teleop
