#include "simpartner/sim/command_queue.h"

#include <algorithm>

namespace simpartner::sim {
namespace {

std::string Describe(const std::string& sender, size_t count, size_t bytes) {
  return "sender '" + sender + "' holds " + std::to_string(count) + " commands, " +
         std::to_string(bytes / 1024) + " KiB";
}

}  // namespace

size_t CommandQueue::BytesOf(const PendingCommand& p) {
  const command_t& c = p.command;
  return sizeof(PendingCommand) + c.sender.size() + c.robot.size() + c.target.size() +
         c.text.size() + sizeof(double) * (c.values.size() + p.values.size());
}

size_t CommandQueue::Share(const Holding& holding) {
  return std::max(holding.count * (kMaxBytes / kMaxCommands), holding.bytes);
}

bool CommandQueue::Fits(size_t bytes) const {
  return entries_.size() < kMaxCommands && bytes_ + bytes <= kMaxBytes;
}

std::string CommandQueue::Add(PendingCommand pending, int64_t now,
                              std::vector<DroppedCommand>* dropped) {
  const size_t bytes = BytesOf(pending);
  const std::string& sender = pending.command.sender;
  if (pending.step > now) {
    while (!Fits(bytes))
      if (!Evict(sender, bytes, now, dropped)) {
        const Holding& own = holdings_[sender];
        const std::string reason =
            "the queue of commands waiting for their step is full (" +
            std::to_string(entries_.size()) + " commands, " + std::to_string(bytes_ / 1024) +
            " KiB; at most " + std::to_string(kMaxCommands) + " commands and " +
            std::to_string(kMaxBytes / (1024 * 1024)) + " MiB), and " +
            Describe(sender, own.count, own.bytes) +
            ", no less than any other sender: send commands closer to their apply_at_step";
        if (own.count == 0) holdings_.erase(sender);
        return reason;
      }
  }
  Holding& holding = holdings_[sender];
  ++holding.count;
  holding.bytes += bytes;
  bytes_ += bytes;
  pending.sequence = next_sequence_++;
  const std::pair<int64_t, uint64_t> key(pending.step, pending.sequence);
  entries_.emplace(key, std::move(pending));
  return "";
}

bool CommandQueue::Evict(const std::string& sender, size_t bytes, int64_t now,
                         std::vector<DroppedCommand>* dropped) {
  Holding would_hold = holdings_.count(sender) ? holdings_.at(sender) : Holding{};
  ++would_hold.count;
  would_hold.bytes += bytes;
  const std::string* largest = nullptr;
  size_t largest_share = Share(would_hold);
  for (const auto& [name, holding] : holdings_)
    if (name != sender && Share(holding) > largest_share) {
      largest = &name;
      largest_share = Share(holding);
    }
  if (largest == nullptr) return false;
  // Its latest command not yet due: the one that waits longest.
  for (auto it = entries_.rbegin(); it != entries_.rend() && it->second.step > now; ++it) {
    const PendingCommand& latest = it->second;
    if (latest.command.sender != *largest) continue;
    const Holding& held = holdings_.at(*largest);
    dropped->push_back(
        {latest.command,
         "dropped from the queue of commands waiting for their step: it was full, " +
             Describe(*largest, held.count, held.bytes) + ", the largest share, and sender '" +
             sender + "' sent a command with less"});
    Release(latest);
    entries_.erase(std::next(it).base());
    return true;
  }
  return false;
}

void CommandQueue::Release(const PendingCommand& pending) {
  const size_t bytes = BytesOf(pending);
  bytes_ -= bytes;
  auto holding = holdings_.find(pending.command.sender);
  holding->second.bytes -= bytes;
  if (--holding->second.count == 0) holdings_.erase(holding);
}

void CommandQueue::Clear() {
  entries_.clear();
  holdings_.clear();
  bytes_ = 0;
}

}  // namespace simpartner::sim
