// Accepted commands waiting for their step, in the order they apply (step,
// then arrival). The queue is bounded in count and bytes (5,000 commands
// dated far ahead once took 256 MB) and shared fairly among senders: when
// it is full, a sender holding a smaller share than another takes the room
// of the other's latest command, so one sender's flood cannot refuse
// another's commands (max-min fairness by each sender's dominant share of
// the two bounds). A sender is the command's `sender` text; on a signed bus
// only the key's holders can send.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "simpartner/command_t.hpp"
#include "simpartner/sim/controllers.h"

namespace simpartner::sim {

struct PendingCommand {
  int64_t step = 0;             // apply when the sim is at this step
  uint64_t sequence = 0;        // arrival order (set by the queue)
  command_t command;
  int actuator = -1;            // exactly one of actuator/sensor is set
  int sensor = -1;
  ParsedCommand parsed;         // actuators
  std::vector<double> values;   // sensors
};

// A command the queue let go before its step, and why.
struct DroppedCommand {
  command_t command;
  std::string reason;
};

class CommandQueue {
 public:
  static constexpr size_t kMaxCommands = 10000;
  static constexpr size_t kMaxBytes = 16u << 20;

  // Queues pending; "" when it went in, else why not. A command due at
  // `now` (its step is not after it) always goes in: it leaves the queue in
  // that step, so a full queue cannot lock out control. Commands taken out
  // to make room are added to *dropped.
  std::string Add(PendingCommand pending, int64_t now, std::vector<DroppedCommand>* dropped);

  // Calls apply for each command due at now, in order, and forgets them.
  template <typename Apply>
  void TakeDue(int64_t now, Apply&& apply) {
    while (!entries_.empty() && entries_.begin()->second.step <= now) {
      const auto first = entries_.begin();
      apply(static_cast<const PendingCommand&>(first->second));
      Release(first->second);
      entries_.erase(first);
    }
  }

  void Clear();

 private:
  struct Holding {
    size_t count = 0;
    size_t bytes = 0;
  };

  static size_t BytesOf(const PendingCommand& pending);
  // A holding's dominant share in bytes: its bytes, or its count in units
  // of kMaxBytes / kMaxCommands, whichever is the larger part of its bound.
  static size_t Share(const Holding& holding);
  bool Fits(size_t bytes) const;
  // Takes the room of the latest command not yet due of the sender with
  // the largest share, when that share is above what sender would hold
  // with `bytes` more; false when none is.
  bool Evict(const std::string& sender, size_t bytes, int64_t now,
             std::vector<DroppedCommand>* dropped);
  void Release(const PendingCommand& pending);

  // By (step, sequence): the order they apply in.
  std::map<std::pair<int64_t, uint64_t>, PendingCommand> entries_;
  size_t bytes_ = 0;                     // BytesOf summed over entries_
  std::map<std::string, Holding> holdings_;  // entries_ per sender
  uint64_t next_sequence_ = 0;
};

}  // namespace simpartner::sim
