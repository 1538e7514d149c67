#include "simpartner/sim/lock_step.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "simpartner/random_token.h"
#include "simpartner/sender.h"

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
  sync_reply_t refusal = Reply(message, sync_reply_t::EVENT_REFUSED, message.period,
                               message.tick, std::move(reason));
  refusal.token = message.token;  // whose mark it was (sync_reply_t.lcm)
  return Outcome{refusal, true};
}

LockStep::Outcome LockStep::Handle(const sync_t& message, int64_t step, const Origin& origin) {
  switch (message.action) {
    case sync_t::ACTION_JOIN: return Join(message, step, origin);
    case sync_t::ACTION_LEAVE: return Leave(message, origin);
    case sync_t::ACTION_DONE: return Done(message, step, origin);
    default:
      return Refuse(message, "unknown action " + std::to_string(message.action) + " from " +
                                 Quoted(message.sender));
  }
}

LockStep::Outcome LockStep::Join(const sync_t& message, int64_t step, const Origin& origin) {
  if (message.controller.empty()) return Refuse(message, "a JOIN needs a controller name");
  if (message.period < 1 || message.period > kMaxPeriod)
    return Refuse(message, "period " + std::to_string(message.period) + " of " +
                               Quoted(message.controller) + " is out of range [1, " +
                               std::to_string(kMaxPeriod) + "] steps");
  const auto it = controllers_.find(message.controller);
  if (it != controllers_.end()) {
    // The same controller asking again (its JOINED was lost): the same
    // answer, token included, only for its own nonce and link.
    const Controller& c = it->second;
    if (c.sender == message.sender && c.period == message.period && !c.join_nonce.empty() &&
        SameToken(message.token, c.join_nonce) && (c.link == 0 || origin.link == c.link)) {
      sync_reply_t again = Reply(message, sync_reply_t::EVENT_JOINED, c.period, c.first_tick, "");
      again.token = c.token;
      return Outcome{again, false};
    }
    return Refuse(message, "controller name " + Quoted(message.controller) + " is in use by " +
                               Quoted(c.sender) + " (period " + std::to_string(c.period) + ")");
  }
  if (const std::string wait = StillWaiting(message, origin.now); !wait.empty())
    return Refuse(message, wait);
  const size_t own = static_cast<size_t>(
      std::count_if(controllers_.begin(), controllers_.end(),
                    [&](const auto& entry) { return entry.second.sender == message.sender; }));
  if (own >= kMaxControllersPerSender)
    return Refuse(message, "sender " + Quoted(message.sender) + " has " + std::to_string(own) +
                               " synchronous controllers already (at most " +
                               std::to_string(kMaxControllersPerSender) + " a sender)");
  if (controllers_.size() >= kMaxControllers)
    return Refuse(message, "already " + std::to_string(kMaxControllers) +
                               " synchronous controllers");
  Controller c;
  c.sender = message.sender;
  c.token = RandomToken();
  c.join_nonce = message.token;
  c.link = origin.link;
  c.period = message.period;
  c.first_tick = (step + message.period - 1) / message.period * message.period;
  controllers_.emplace(message.controller, c);
  sync_reply_t joined = Reply(message, sync_reply_t::EVENT_JOINED, c.period, c.first_tick, "");
  joined.token = c.token;
  return Outcome{joined, false};
}

std::string LockStep::StillWaiting(const sync_t& message, Clock::time_point now) const {
  const auto wait_of = [now](const std::map<std::string, Releases>& releases,
                             const std::string& key, const std::string& who) -> std::string {
    const auto it = releases.find(key);
    if (it == releases.end() || now >= it->second.not_before) return "";
    const auto wait = std::chrono::ceil<std::chrono::seconds>(it->second.not_before - now);
    return who + " was released " + std::to_string(it->second.count) +
           (it->second.count == 1 ? " time" : " times") + " for not answering (last at tick " +
           std::to_string(it->second.tick) + "); it may join again in " +
           std::to_string(wait.count()) + " s";
  };
  const std::string why =
      wait_of(released_, message.controller, "controller " + Quoted(message.controller));
  return !why.empty() ? why
                      : wait_of(released_senders_, message.sender, "sender " + Quoted(message.sender));
}

std::string LockStep::NotItsOwn(const sync_t& message, const Controller& c,
                                const Origin& origin) {
  const std::string what =
      (message.action == sync_t::ACTION_LEAVE ? "LEAVE of " : "done mark of ") +
      Quoted(message.controller);
  if (c.sender != message.sender)
    return what + " from " + Quoted(message.sender) + "; it joined from " + Quoted(c.sender);
  if (!SameToken(message.token, c.token))
    return what + " without the token its JOINED gave: only the controller itself acts for it";
  if (c.link != 0 && origin.link != c.link)
    return what + " from another signing link than its JOIN's: only the controller itself "
                  "acts for it";
  return "";
}

LockStep::Outcome LockStep::Leave(const sync_t& message, const Origin& origin) {
  const auto it = controllers_.find(message.controller);
  if (it == controllers_.end())
    return Refuse(message, "LEAVE from " + Quoted(message.controller) + ", which has not joined");
  if (const std::string why = NotItsOwn(message, it->second, origin); !why.empty())
    return Refuse(message, why);
  const Controller c = it->second;
  controllers_.erase(it);
  sync_reply_t left = Reply(message, sync_reply_t::EVENT_LEFT, c.period, c.last_done, "");
  left.token = c.token;
  return Outcome{left, false};
}

LockStep::Outcome LockStep::Done(const sync_t& message, int64_t step, const Origin& origin) {
  const std::string who = Quoted(message.controller);
  const std::string tick = std::to_string(message.tick);
  const auto it = controllers_.find(message.controller);
  if (it == controllers_.end()) {
    const auto released = released_.find(message.controller);
    if (released != released_.end())
      return Refuse(message, "done mark of " + who + " for tick " + tick +
                                 ": released at tick " + std::to_string(released->second.tick) +
                                 " (no answer in time); join again");
    return Refuse(message, "done mark of " + who + " for tick " + tick + ": it has not joined");
  }
  Controller& c = it->second;
  if (const std::string why = NotItsOwn(message, c, origin); !why.empty())
    return Refuse(message, why);
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
    // It answers: its earlier releases are forgiven.
    released_.erase(name);
    released_senders_.erase(c.sender);
  }
  return commands;
}

void LockStep::Remember(std::map<std::string, Releases>* releases, const std::string& key,
                        int64_t tick, Clock::time_point now) {
  if (releases->count(key) == 0 && releases->size() >= kMaxReleasesRemembered)
    releases->erase(std::min_element(releases->begin(), releases->end(),
                                     [](const auto& a, const auto& b) {
                                       return a.second.not_before < b.second.not_before;
                                     }));
  Releases& r = (*releases)[key];
  ++r.count;
  r.tick = tick;
  const auto wait = kRejoinWaitFirst * (int64_t{1} << std::min(r.count - 1, 10));
  r.not_before = now + std::min<Clock::duration>(wait, kRejoinWaitMost);
}

std::vector<sync_reply_t> LockStep::ReleaseWaiting(int64_t step, const std::string& reason,
                                                   Clock::time_point now) {
  std::vector<sync_reply_t> replies;
  for (const std::string& name : WaitingOn(step)) {
    const Controller c = controllers_.at(name);
    sync_t message{};
    message.controller = name;
    message.sender = c.sender;
    replies.push_back(Reply(message, sync_reply_t::EVENT_RELEASED, c.period, step, reason));
    replies.back().token = c.token;
    Remember(&released_, name, step, now);
    Remember(&released_senders_, c.sender, step, now);
    controllers_.erase(name);
  }
  return replies;
}

void LockStep::Clear() {
  controllers_.clear();
  released_.clear();
  released_senders_.clear();
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
