#include "simpartner/sim/sim_command_line.h"

#include "simpartner/model/loader.h"
#include "simpartner/model/robot_choice.h"
#include "simpartner/sim/engine.h"

namespace simpartner::sim {

CommandLineSpec SimCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-sim";
  spec.summary =
      "The SimPartner physics process: loads the parameters, the world (parameter 'environment') "
      "and its robots, steps the physics engine (ODE or MuJoCo, parameter 'engine') at a "
      "fixed step and serves the simulation over LCM. World and "
      "robot files are found as given, else under $SIMPARTNER_DATA, the source tree (a build's "
      "programs) or the install's share/simpartner, also by file name alone "
      "(--environment=maze.xml).";
  spec.options = {
      Switch("check",
             "load and validate the parameters, the world and its robots, print a summary and "
             "exit (0 = all good)"),
      Text("robot", "NAME|FILE",
           "put this robot into the world instead of the world's robots: gen1, gen1-light, "
           "gen2, gen3, gen4 or a robot file (keeps the first robot's instance name and pose)"),
      Text("robot-pose", "X,Y,Z[,YAW]",
           "where --robot stands: world coordinates [m] (y is up in the shipped worlds), yaw "
           "[deg] about the up axis (default: the world's first robot's pose, else the origin)"),
      Switch("robot-add", "add the --robot beside the world's robots instead of replacing them"),
      Switch("allow-other-sims",
             "start even when another simulation is heard on the bus (by default the sim asks "
             "for SIM_MODEL first and refuses to start if another sim answers)"),
  };
  spec.epilogue =
      "Exit status: 0 the run ended (its duration, SIM_CONTROL quit, SIGINT or SIGTERM); 1 an "
      "error while running; 2 bad input (parameters, world, robot), nothing started; 3 another "
      "simulation is on the bus, nothing started; 4 the run faulted (an exploding or non-finite "
      "state, or the engine gave up) before its --duration, which a faulted sim cannot reach without a "
      "reset.";
  spec.parameters = ParameterUse{{parameter_sections::kWorld, parameter_sections::kStepping,
                                  parameter_sections::kContact, parameter_sections::kRunning,
                                  parameter_sections::kTransport}};
  return spec;
}

namespace {

// What the chosen engine cannot represent is refused here, at --check and
// before anything starts, never approximated silently.
model::World RefuseWhatTheEngineCannotRun(model::World world, const Parameters& params) {
  const model::FlatModel flat = model::Flatten(world);
  DiagnosticList list;
  for (Diagnostic& d : EngineLimits(flat, params)) list.Add(std::move(d));
  if (!list.empty()) throw DiagnosticError(list);
  return world;
}

}  // namespace

model::World LoadSimWorld(const CommandLine& command_line, const Parameters& params) {
  return RefuseWhatTheEngineCannotRun(LoadWorldWithRobot(command_line, params), params);
}

model::World LoadWorldWithRobot(const CommandLine& command_line, const Parameters& params) {
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
  choice.robot = command_line.Text("robot");
  choice.add = command_line.Has("robot-add");
  if (command_line.Has("robot-pose"))
    model::ParseRobotPose(command_line.Text("robot-pose"), &choice);
  model::PlaceRobot(choice, &world);
  return world;
}

}  // namespace simpartner::sim
