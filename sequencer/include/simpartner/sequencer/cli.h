// simpartner-sequencer's command line, as a function the tests call.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "simpartner/command_line.h"

namespace simpartner::sequencer {

// Runs the program with `args` (without the program name); returns the
// exit status (ExitCode). stop_fd: see PlayOptions::stop_fd.
int RunSequencer(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                 int stop_fd = -1);

// What simpartner-sequencer takes on its command line.
CommandLineSpec SequencerCommandLine();

}  // namespace simpartner::sequencer
