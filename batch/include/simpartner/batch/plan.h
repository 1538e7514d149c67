// The runs of a batch: the sweep's combinations (grid) or rows (list),
// each once per seed, numbered from 0 in a fixed order, so run i is the
// same run wherever and whenever it runs (a resumed batch, a Slurm array
// task). No processes here: the plan is what the runner and the Slurm job
// share.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "simpartner/batch/batch_file.h"

namespace simpartner::batch {

struct PlannedRun {
  int index = 0;
  long long seed = 0;
  // The sweep's values of this run, in the order of the sweep.
  std::vector<std::pair<std::string, std::string>> values;
  // Every parameter of the sim: the fixed ones, then the swept ones.
  std::vector<std::pair<std::string, std::string>> parameters;
};

std::vector<PlannedRun> PlanRuns(const BatchFile& batch);

// The controller's argv for `run` on `url`: the command split at blanks,
// each {placeholder} replaced (url, seed, run, batch, the variables).
std::vector<std::string> ControllerArgv(const BatchFile& batch, const PlannedRun& run,
                                        const std::string& url);

// "contactMu=0.5 x=3 seed=2": what tags the run's Simulation row.
std::string RunTag(const BatchFile& batch, const PlannedRun& run);

}  // namespace simpartner::batch
