// SIGINT and SIGTERM as a file descriptor a program's loop watches beside
// its other input, so that a stop request (Ctrl-C, a supervisor, a CI
// timeout) ends the run through its normal path (a last status, wheels to
// zero) instead of killing the process mid-step.
#pragma once

namespace simpartner {

// Blocks SIGINT and SIGTERM in the calling thread (call it before starting
// threads, which inherit the mask) and returns a non-blocking signalfd that
// becomes readable when one arrives; -1 when none can be made (errno set).
int BlockStopSignalsIntoFd();

}  // namespace simpartner
