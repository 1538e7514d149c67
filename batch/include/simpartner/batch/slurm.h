// The same batch on a cluster: the runs not done yet go to Slurm as one
// job array (sbatch --array), each task one run: simpartner-batch itself
// with --only $SLURM_ARRAY_TASK_ID, writing its result into the shared
// results folder and logging into the database the batch names. This side
// only submits, waits and collects; Slurm places, retries and accounts.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/batch/batch_file.h"
#include "simpartner/batch/plan.h"
#include "simpartner/batch/runner.h"
#include "simpartner/diagnostic.h"

namespace simpartner::batch {

// Slurm is not there, refuses the job, or does not answer: what and how to
// find out more.
class SlurmError : public Error {
 public:
  using Error::Error;
};

struct SlurmOptions {
  std::string partition;                 // "" = the cluster's default
  std::vector<std::string> sbatch_args;  // more for sbatch, e.g. --account=X
  double answer_timeout = 60;            // [s] an sbatch or squeue call may take
  double poll_period = 2;                // [s] between looks at the queue
};

// Submits the runs of `runs` that have no good result yet, waits until
// the job has left the queue, and returns what the runs left in the
// results folder (as RunBatch does). Throws SlurmError.
BatchOutcome RunOnSlurm(const BatchFile& batch, const std::vector<PlannedRun>& runs,
                        const BatchOptions& options, const SlurmOptions& slurm,
                        std::ostream& progress_out);

}  // namespace simpartner::batch
