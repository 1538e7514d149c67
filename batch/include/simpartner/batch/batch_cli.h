// simpartner-batch's command line and the program around the library:
// check the file, plan, run here N at a time (or on Slurm: slurm.h),
// write the summary.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/command_line.h"

namespace simpartner::batch {

CommandLineSpec BatchCommandLine();

// The whole program after its command line was read. Exit status: 0 every
// run ok; 1 some run failed or is missing; 2 the batch file or the command
// line is wrong (nothing started).
int RunBatchProgram(const CommandLine& command_line, std::ostream& out, std::ostream& err);

}  // namespace simpartner::batch
