// One run of a batch, as its own processes on its own bus: a logger (when
// the batch logs), the sim (paused at start, as fast as possible, for the
// batch's duration) and the controller or sequencer; the run's figures and
// the hash of its SIM_STATE stream taken from the bus meanwhile. Its logs
// and result go into <results>/runs/<index>/.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "simpartner/batch/batch_file.h"
#include "simpartner/batch/plan.h"

namespace simpartner::batch {

struct RunContext {
  std::string results_dir;
  double timeout = 600;  // [s] of wall time a run may take
  bool log = true;       // a simpartner-logger per run
  std::vector<std::string> logger_args;  // --db-options F, --dbname N, --dbserver S ...
};

struct RunResult {
  int index = 0;
  bool ok = false;
  std::string status;        // "ok", or what failed and how ("sim exit 3", "timeout after 600 s")
  std::string tag;           // RunTag(): the run's values
  int64_t last_step = -1;
  double sim_time = 0;
  double wall_seconds = 0;
  std::string state_hash;    // 16 hex digits of FNV-1a over the states; "" when one was missed
  int64_t states = 0;        // SIM_STATEs received
  std::vector<double> figures;  // in the batch file's order; NaN when the body was missing
  std::string log_dir;
};

// Runs it to its end (or the timeout); never throws for a run that fails:
// the result says how, and the logs stay.
RunResult RunOne(const BatchFile& batch, const PlannedRun& run, const RunContext& context);

// <results>/runs/<index>/result.txt: written at a run's end, read to skip
// runs already done when a batch is run again.
std::string ResultPath(const std::string& results_dir, int index);
void WriteResult(const RunResult& result, const std::string& path);
// Nothing when there is no such file or it cannot be read.
std::optional<RunResult> ReadResult(const std::string& path);

}  // namespace simpartner::batch
