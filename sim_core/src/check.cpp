#include "simpartner/sim/check.h"

#include "simpartner/model/loader.h"
#include "simpartner/model/robot_choice.h"

namespace simpartner::sim {

const std::vector<FlagSpec>& SimFlags() {
  static const std::vector<FlagSpec> kFlags = {
      {"check", false,
       "load and validate the parameters, the world and its robots, print a "
       "summary and exit (0 = all good)"},
      {"robot", true,
       "put this robot into the world instead of the world's robots: gen1, gen1-light, "
       "gen2, gen3, gen4 or a robot file (keeps the first robot's instance name and pose)"},
      {"robot-pose", true,
       "x,y,z[,yaw] where --robot stands: world coordinates [m] (y is up in the shipped "
       "worlds), yaw [deg] about the up axis (default: the world's first robot's pose, else "
       "the origin)"},
      {"robot-add", false, "add the --robot beside the world's robots instead of replacing them"},
      {"allow-other-sims", false,
       "start even when another simulation is heard on the bus (by default the sim "
       "asks for SIM_MODEL first and refuses to start if another sim answers)"},
  };
  return kFlags;
}

const char* SimSummary() {
  return "The SimPartner physics process: loads the parameters, the world "
         "(parameter 'environment') and its robots, steps ODE at a fixed step "
         "and serves the simulation over LCM. World and robot files are found as "
         "given, else under $SIMPARTNER_DATA, the source tree (a build's programs) or "
         "the install's share/simpartner, also by file name alone (--environment=maze.xml).";
}

model::World LoadSimWorld(const CommandLine& command_line, const Parameters& params) {
  model::World world = model::LoadWorldOrThrow(params.environment);
  if (!command_line.Has("robot")) {
    for (const char* flag : {"robot-pose", "robot-add"}) {
      if (command_line.Has(flag)) {
        DiagnosticList list;
        list.Add("command line", 0, std::string("--") + flag, "goes with --robot NAME|FILE");
        throw ConfigError(list);
      }
    }
    return world;
  }
  model::RobotChoice choice;
  choice.robot = command_line.Value("robot", "");
  choice.add = command_line.Has("robot-add");
  if (command_line.Has("robot-pose"))
    model::ParseRobotPose(command_line.Value("robot-pose", ""), &choice);
  model::PlaceRobot(choice, &world);
  return world;
}

}  // namespace simpartner::sim
