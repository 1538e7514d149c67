// What the wheels of a gen1 gait on ice do in each phase of its cycle, at
// several steps: the body's speed against one stride per cycle, and per
// phase each wheel's displacement, how much of it it rolled (and how much
// of that its calf's turn gave) and how much it slid, with the ground's
// mean friction against mu times its load. The rolking experiment's
// figures (docs/validation.md, rolking) come from
//   bench/gait_slip            (rolking at 2, 1, 0.5 and 0.25 ms)
//   bench/gait_slip --gait caterpillar 0.001
#include <iostream>
#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/text.h"
#include "simpartner/validate/gait.h"

namespace {

using namespace simpartner;
using namespace simpartner::validate;

constexpr double kIceMu = 0.025;  // slippery_ground.xml

void PrintRun(const Context& context, const GaitSequence& gait, std::ostream& out) {
  const GaitRun run = RunGait(context, gait);
  const double stride_speed = gait.stride / gait.CycleTime();
  out << "## " << gait.file << " at " << FormatNumber(context.params.stepsize * 1000.0) << " ms: "
      << FormatNumber(run.speed) << " m/s, " << FormatFixed((run.speed / stride_speed - 1.0) * 100.0, 2)
      << " % over stride / cycle (" << run.cycles - 1 << " cycles measured)\n\n"
      << PhaseSlipTable(run.phases, kIceMu) << "\n";
  out.flush();
}

}  // namespace

int main(int argc, char** argv) {
  CommandLineSpec spec;
  spec.program = "gait_slip";
  spec.summary =
      "Plays a gen1 gait on ice (slippery_ground.xml) at each step given (default 0.002 0.001 "
      "0.0005 0.00025 s) and prints, per phase of the cycle and per wheel, what it moved, rolled "
      "and slid and the ground's friction against mu times its load (means per cycle over the "
      "cycles after the first).";
  spec.options = {
      Text("gait", "rolking|caterpillar", "the gait (default rolking)").Choices({"rolking", "caterpillar"}),
      Switch("quick", "three cycles, as the unit tests play them"),
      Text("models", "DIR",
           "directory holding worlds/ and robots/, its sequences/ beside it (default: the "
           "source tree's models/)"),
  };
  spec.positionals = {Positional{"STEP", 0, kAnyCount}};
  spec.parameters = ParameterUse{};
  CommandLine args;
  if (const auto done = ReadCommandLine(spec, {argv + 1, argv + argc}, std::cout, std::cerr, &args))
    return *done;
  std::vector<std::string> steps = args.positional();
  if (steps.empty()) steps = {"0.002", "0.001", "0.0005", "0.00025"};
  try {
    Context context;
    context.models_dir = args.Text("models", std::string(SP_SOURCE_DIR) + "/models");
    context.quick = args.Has("quick");
    const GaitSequence gait =
        args.Text("gait", "rolking") == "rolking" ? RollingWalkingSequence() : CaterpillarSequence();
    for (const std::string& step : steps) {
      // As --stepsize=STEP: checked (and refused with its value) like any key.
      ParameterSources sources = args.parameter_sources();
      sources.overrides.emplace_back("stepsize", step);
      context.params = LoadParameters(sources);
      PrintRun(context, gait, std::cout);
    }
  } catch (const std::exception& e) {
    std::cerr << "gait_slip: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
