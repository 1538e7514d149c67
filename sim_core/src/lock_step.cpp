#include "simpartner/sim/lock_step.h"
#include "simpartner/sender.h"

#include <chrono>
#include <utility>

namespace simpartner::sim {
namespace {

std::string Quoted(const std::string& name) { return "'" + name + "'"; }

}  // namespace

sync_reply_t LockStep::Reply(const sync_t& message, int8_t event, int64_t period, int64_t tick,
                             std::string reason) {
  sync_reply_t reply{};
  reply.utime = WallMicros();
  reply.simulation_id = message.simulation_id;
  reply.controller = message.controller;
  reply.sender = message.sender;
  reply.event = event;
  reply.period = period;
  reply.tick = tick;
  reply.reason = std::move(reason);
  return reply;
}

LockStep::Outcome LockStep::Refuse(const sync_t& message, std::string reason) {
  return Outcome{Reply(message, sync_reply_t::EVENT_REFUSED, message.period, message.tick,
                       std::move(reason)),
                 true};
}

LockStep::Outcome LockStep::Handle(const sync_t& message, int64_t step) {
  switch (message.action) {
    case sync_t::ACTION_JOIN: return Join(message, step);
    case sync_t::ACTION_LEAVE: return Leave(message);
    case sync_t::ACTION_DONE: return Done(message, step);
    default:
      return Refuse(message, "unknown action " + std::to_string(message.action) + " from " +
                                 Quoted(message.sender));
  }
}

LockStep::Outcome LockStep::Join(const sync_t& message, int64_t step) {
  if (message.controller.empty()) return Refuse(message, "a JOIN needs a controller name");
  if (message.period < 1 || message.period > kMaxPeriod)
    return Refuse(message, "period " + std::to_string(message.period) + " of " +
                               Quoted(message.controller) + " is out of range [1, " +
                               std::to_string(kMaxPeriod) + "] steps");
  const auto it = controllers_.find(message.controller);
  if (it != controllers_.end()) {
    // The same process asking again (its JOINED was lost): the same answer.
    if (it->second.sender == message.sender && it->second.period == message.period)
      return Outcome{Reply(message, sync_reply_t::EVENT_JOINED, it->second.period,
                           it->second.first_tick, ""),
                     false};
    return Refuse(message, "controller name " + Quoted(message.controller) + " is in use by " +
                               Quoted(it->second.sender) + " (period " +
                               std::to_string(it->second.period) + ")");
  }
  if (controllers_.size() >= kMaxControllers)
    return Refuse(message, "already " + std::to_string(kMaxControllers) +
                               " synchronous controllers");
  Controller c;
  c.sender = message.sender;
  c.period = message.period;
  c.first_tick = (step + message.period - 1) / message.period * message.period;
  controllers_.emplace(message.controller, c);
  released_.erase(message.controller);
  return Outcome{Reply(message, sync_reply_t::EVENT_JOINED, c.period, c.first_tick, ""), false};
}

LockStep::Outcome LockStep::Leave(const sync_t& message) {
  const auto it = controllers_.find(message.controller);
  if (it == controllers_.end())
    return Refuse(message, "LEAVE from " + Quoted(message.controller) + ", which has not joined");
  if (it->second.sender != message.sender)
    return Refuse(message, "LEAVE of " + Quoted(message.controller) + " from " +
                               Quoted(message.sender) + "; it joined from " +
                               Quoted(it->second.sender));
  const Controller c = it->second;
  controllers_.erase(it);
  return Outcome{Reply(message, sync_reply_t::EVENT_LEFT, c.period, c.last_done, ""), false};
}

LockStep::Outcome LockStep::Done(const sync_t& message, int64_t step) {
  const std::string who = Quoted(message.controller);
  const std::string tick = std::to_string(message.tick);
  const auto it = controllers_.find(message.controller);
  if (it == controllers_.end()) {
    const auto released = released_.find(message.controller);
    if (released != released_.end())
      return Refuse(message, "done mark of " + who + " for tick " + tick +
                                 ": released at tick " + std::to_string(released->second) +
                                 " (no answer in time); join again");
    return Refuse(message, "done mark of " + who + " for tick " + tick + ": it has not joined");
  }
  Controller& c = it->second;
  if (c.sender != message.sender)
    return Refuse(message, "done mark of " + who + " from " + Quoted(message.sender) +
                               "; it joined from " + Quoted(c.sender));
  if (message.tick == c.last_done || message.tick == c.answered_tick)
    return Refuse(message, "duplicate done mark of " + who + " for tick " + tick);
  if (message.tick > step)
    return Refuse(message, "done mark of " + who + " for tick " + tick +
                               ", which has not happened (the sim is at step " +
                               std::to_string(step) + ")");
  if (message.tick < step)
    return Refuse(message, "done mark of " + who + " for tick " + tick +
                               ", which has passed (the sim is at step " + std::to_string(step) +
                               ")");
  if (!c.DueAt(step))
    return Refuse(message, "done mark of " + who + " for step " + tick +
                               ", which is not one of its ticks (every " +
                               std::to_string(c.period) + " steps from " +
                               std::to_string(c.first_tick) + ")");
  c.answered_tick = step;
  c.answer = message.commands;
  return Outcome{};
}

bool LockStep::IsTick(int64_t step) const {
  for (const auto& [name, c] : controllers_)
    if (c.DueAt(step)) return true;
  return false;
}

std::vector<std::string> LockStep::WaitingOn(int64_t step) const {
  std::vector<std::string> names;
  for (const auto& [name, c] : controllers_)
    if (c.DueAt(step) && c.answered_tick != step) names.push_back(name);
  return names;
}

std::vector<command_t> LockStep::TakeAnswers(int64_t step) {
  std::vector<command_t> commands;
  for (auto& [name, c] : controllers_) {
    if (c.answered_tick != step || c.last_done == step) continue;
    for (command_t& command : c.answer) {
      command.apply_at_step = step;
      commands.push_back(std::move(command));
    }
    c.answer.clear();
    c.last_done = step;
  }
  return commands;
}

std::vector<sync_reply_t> LockStep::ReleaseWaiting(int64_t step, const std::string& reason) {
  std::vector<sync_reply_t> replies;
  for (const std::string& name : WaitingOn(step)) {
    const Controller c = controllers_.at(name);
    sync_t message{};
    message.controller = name;
    message.sender = c.sender;
    replies.push_back(Reply(message, sync_reply_t::EVENT_RELEASED, c.period, step, reason));
    released_[name] = step;
    controllers_.erase(name);
  }
  return replies;
}

void LockStep::Clear() {
  controllers_.clear();
  released_.clear();
}

std::vector<sync_controller_t> LockStep::Describe(int64_t step) const {
  std::vector<sync_controller_t> out;
  for (const auto& [name, c] : controllers_) {
    sync_controller_t d{};
    d.controller = name;
    d.sender = c.sender;
    d.period = c.period;
    d.first_tick = c.first_tick;
    d.last_done = c.last_done;
    d.waited_on = c.DueAt(step) && c.answered_tick != step;
    out.push_back(d);
  }
  return out;
}

}  // namespace simpartner::sim
