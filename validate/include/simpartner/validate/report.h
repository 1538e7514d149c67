// Output of a validation run: the one-line-per-check text for the terminal
// and the Markdown report with its plots.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/validate/experiment.h"

namespace simpartner::validate {

// "name  label  measured  target  tolerance  PASS|FAIL" for each check, or
// "name  ERROR: reason" for a run that failed.
void PrintResult(const ExperimentResult& result, std::ostream& out);

// Writes directory/README.md and a PNG per plot (gnuplot). `command` is the
// command line that produced it, shown in the report so it can be rerun.
// Throws simpartner::Error when the directory cannot be written or a plot
// cannot be drawn.
void WriteReport(const std::string& directory, const std::vector<ExperimentResult>& results,
                 const std::string& command, const Parameters& params);

}  // namespace simpartner::validate
