// A whole batch on this machine: its runs N at a time, each run's result
// written as it ends, runs already done (a result with "ok" and the same
// values) skipped, a progress line, and the summary table at the end.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/batch/batch_file.h"
#include "simpartner/batch/plan.h"
#include "simpartner/batch/run.h"

namespace simpartner::batch {

struct BatchOptions {
  RunContext run;
  int parallel = 1;            // runs at a time
  std::vector<int> only;       // run these indices only (a Slurm array task); empty: all
  bool progress = true;        // the progress line on `progress_out`
};

struct BatchOutcome {
  int done = 0;      // ran now and ok
  int failed = 0;    // ran now and failed
  int skipped = 0;   // done before (resumed)
  std::vector<RunResult> results;  // every planned run that has a result, by index
};

BatchOutcome RunBatch(const BatchFile& batch, const std::vector<PlannedRun>& runs,
                      const BatchOptions& options, std::ostream& progress_out);

// <results>/summary.csv: a row per run with its values, seed, status,
// steps, sim time, wall time, state hash, the figures and the log folder.
std::string SummaryPath(const std::string& results_dir);
void WriteSummary(const BatchFile& batch, const std::vector<PlannedRun>& runs,
                  const std::vector<RunResult>& results, const std::string& path);

// The results of `runs` found under results_dir (done before or by Slurm
// tasks), by index; a run without one is missing.
std::vector<RunResult> CollectResults(const std::vector<PlannedRun>& runs,
                                      const BatchFile& batch, const std::string& results_dir);

}  // namespace simpartner::batch
