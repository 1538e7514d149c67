#include "simpartner/simulation_follower.h"

#include <algorithm>

#include "simpartner/status_t.hpp"

namespace simpartner {

bool EndsSimulation(int8_t run_state) {
  return run_state == status_t::RUN_STOPPED || run_state == status_t::RUN_RESET;
}

SimulationFollower::Verdict SimulationFollower::OnModel(int64_t id, Clock::time_point now) {
  if (WasFollowed(id)) {
    if (id == followed_) followed_heard_ = now;
    return Verdict::kKnown;
  }
  if (followed_ == 0 || FollowedIsGone(now)) {
    Follow(id, now);
    return Verdict::kFollow;
  }
  // A model is no sign of life (a copy is one): only its states and
  // status are (Heard).
  const bool is_new = others_.emplace(id, Clock::time_point{}).second;
  if (is_new && others_.size() > kMaxOthers) {
    const auto oldest = std::min_element(
        others_.begin(), others_.end(),
        [](const auto& a, const auto& b) { return a.second < b.second; });
    others_.erase(oldest);
  }
  return Verdict::kOther;
}

void SimulationFollower::Heard(int64_t id, Clock::time_point now) {
  if (id == followed_) {
    followed_heard_ = now;
  } else if (const auto other = others_.find(id); other != others_.end()) {
    other->second = now;
  }
}

void SimulationFollower::Ended(int64_t id) {
  if (id == followed_) followed_ended_ = true;
}

std::optional<int64_t> SimulationFollower::TakeSuccessor(Clock::time_point now) {
  if (others_.empty() || !FollowedIsGone(now)) return std::nullopt;
  // The newest other heard after the followed one last was.
  const auto newest = std::max_element(
      others_.begin(), others_.end(),
      [](const auto& a, const auto& b) { return a.second < b.second; });
  // Silent itself (a copied or stale model, no states behind it): none.
  if (newest->second == Clock::time_point{} || now - newest->second >= silence_)
    return std::nullopt;
  if (!followed_ended_ && newest->second <= followed_heard_) return std::nullopt;
  const int64_t id = newest->first;
  Follow(id, now);
  return id;
}

void SimulationFollower::Attach(int64_t id, Clock::time_point now) { Follow(id, now); }

bool SimulationFollower::FollowedIsGone(Clock::time_point now) const {
  return followed_ended_ || now - followed_heard_ >= silence_;
}

void SimulationFollower::Follow(int64_t id, Clock::time_point now) {
  followed_ = id;
  followed_heard_ = now;
  followed_ended_ = false;
  followed_before_.insert(id);
  others_.erase(id);
}

}  // namespace simpartner
