#include "simpartner/simulation_follower.h"

#include <algorithm>

namespace simpartner {

SimulationFollower::Verdict SimulationFollower::OnModel(int64_t id, const std::string& sender,
                                                        Clock::time_point now) {
  if (WasFollowed(id)) {
    if (id == followed_) followed_heard_ = now;
    if (id == followed_ && !followed_sender_) followed_sender_ = sender;  // attached
    return Verdict::kKnown;
  }
  const bool same_sender = followed_sender_ && sender == *followed_sender_;
  if (followed_ == 0 || same_sender || FollowedIsGone(now)) {
    Follow(id, sender, now);
    return Verdict::kFollow;
  }
  const bool is_new = others_.count(id) == 0;
  others_[id] = Other{sender, now};
  if (is_new && others_.size() > kMaxOthers) {
    const auto oldest = std::min_element(
        others_.begin(), others_.end(),
        [](const auto& a, const auto& b) { return a.second.heard < b.second.heard; });
    others_.erase(oldest);
  }
  return Verdict::kOther;
}

void SimulationFollower::Heard(int64_t id, Clock::time_point now) {
  if (id == followed_) {
    followed_heard_ = now;
  } else if (const auto other = others_.find(id); other != others_.end()) {
    other->second.heard = now;
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
      [](const auto& a, const auto& b) { return a.second.heard < b.second.heard; });
  if (!followed_ended_ && newest->second.heard <= followed_heard_) return std::nullopt;
  const int64_t id = newest->first;
  const std::string sender = newest->second.sender;
  Follow(id, sender, now);
  return id;
}

void SimulationFollower::Attach(int64_t id, Clock::time_point now) {
  Follow(id, "", now);
  followed_sender_.reset();  // the first model of `id` names it
}

bool SimulationFollower::FollowedIsGone(Clock::time_point now) const {
  return followed_ended_ || now - followed_heard_ >= silence_;
}

void SimulationFollower::Follow(int64_t id, const std::string& sender, Clock::time_point now) {
  followed_ = id;
  followed_sender_ = sender;
  followed_heard_ = now;
  followed_ended_ = false;
  followed_before_.insert(id);
  others_.erase(id);
}

}  // namespace simpartner
