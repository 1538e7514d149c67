// Output of a validation run: the one-line-per-check text for the terminal
// and the Markdown report with its plots.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/validate/experiment.h"
#include "simpartner/validate/explanations.h"

namespace simpartner::validate {

// "name  label  measured  target  tolerance  PASS|FAIL" for each check,
// "name  ERROR: reason" for a run that failed, or "name  NOT APPLICABLE:
// reason" for an engine that cannot run it; with name_engine,
// "name  engine  ..." (a run on more than one engine).
void PrintResult(const ExperimentResult& result, std::ostream& out, bool name_engine = false);

// How the report names an engine: "ode" -> "ODE", "mujoco" -> "MuJoCo".
std::string EngineTitle(const std::string& engine);

// Passed and run experiments of one engine, and their sim steps; those
// the engine cannot represent are counted apart, not run.
struct EngineTally {
  std::string engine;
  int passed = 0;
  int run = 0;
  int not_applicable = 0;
  StepTiming stepping;
};
// One tally per engine of results, in the order the engines first appear.
std::vector<EngineTally> TallyByEngine(const std::vector<ExperimentResult>& results);
// "15 of 15 experiments passed on ODE (mean 183 µs per step)", one line
// per engine.
void PrintTallies(const std::vector<EngineTally>& tallies, std::ostream& out);

// A step's wall time for people: "183", "24.1", "0.35" (µs); "-" for NaN.
std::string MicrosecondsText(double microseconds);

// Writes directory/README.md and a PNG per plot (gnuplot). `command` is the
// command line that produced it, shown in the report so it can be rerun.
// A failing check gets its explanation from `explanations`, or "not yet
// explained". Throws simpartner::Error when the directory cannot be
// written or a plot cannot be drawn.
void WriteReport(const std::string& directory, const std::vector<ExperimentResult>& results,
                 const std::string& command, const Parameters& params,
                 const std::vector<Explanation>& explanations = Explanations());

}  // namespace simpartner::validate
