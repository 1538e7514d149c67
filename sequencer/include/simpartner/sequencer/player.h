// Plays a checked sequence against the sim on the bus. Time is the sim's:
// every command carries apply_at_step (its segment's start step plus its
// time in steps), so a timed sequence gives the same run at any speed.
// Commands go out ahead of their step (a window of sim time), and each
// accepted reply prints a progress line with the command's file line.
// A refusal, a restart of the sim (new simulation id), a sim that faults
// or goes silent, or a wait that times out stops the sequence: the
// reason and the file line are printed, every wheel motor (velocity
// controller) is set to zero velocity, and the result is kStopped.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

#include "simpartner/sequencer/sequence.h"

namespace simpartner::sequencer {

enum ExitCode : int {
  kDone = 0,       // every command accepted, every wait met, the end reached
  kStopped = 1,    // stopped while playing (refused, restarted, silent, faulted, wait timed out)
  kInvalid = 2,    // the file or the command line is wrong; nothing was sent
  kNoSim = 3,      // no sim answered on the bus
};

struct PlayOptions {
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  // false: `at` times count from the sim's step when the sequence starts;
  // true: from sim time 0 (a sim started paused, for runs that must match
  // step for step, e.g. the validation's).
  bool from_zero = false;
  bool resume = false;                 // resume a paused sim once the first commands are out
  std::optional<double> speed;         // set the sim's speed first (<= 0: as fast as possible)
  double model_timeout = 3.0;          // [s] wall, for SIM_MODEL
  double silence_timeout = 2.0;        // [s] wall without SIM_STATE or SIM_STATUS
  double window = 1.0;                 // [s] sim time: how far ahead commands are sent
  bool quiet = false;                  // no progress lines
  // Readable when the user asks to stop (main's signalfd of SIGINT and
  // SIGTERM): the sequence stops as on a refusal, wheels to zero. -1: none.
  int stop_fd = -1;
};

// Plays `sequence`; progress goes to `out`, problems to `err`.
ExitCode Play(const Sequence& sequence, const PlayOptions& options, std::ostream& out,
              std::ostream& err);

}  // namespace simpartner::sequencer
