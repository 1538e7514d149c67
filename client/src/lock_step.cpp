#include "simpartner/client/lock_step.h"

#include <algorithm>
#include <limits>

#include "simpartner/client/errors.h"
#include "simpartner/random_token.h"

namespace simpartner::client {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int64_t kMaxPeriod = 1000000;
// A join not answered is asked again this often.
constexpr auto kJoinAgain = std::chrono::milliseconds(250);
// Waiting for a tick's state: a state request (its datagram may have been
// lost) once the tick is this late, and again at this interval.
constexpr auto kStateLate = std::chrono::milliseconds(100);
constexpr auto kStateAgain = std::chrono::milliseconds(200);
constexpr auto kPoll = std::chrono::milliseconds(20);

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// "program" of a sender name "program@host:pid".
std::string ProgramOf(const std::string& sender) { return sender.substr(0, sender.find('@')); }

}  // namespace

LockStep::LockStep(Client& client, LockStepOptions options)
    : client_(client), options_(std::move(options)) {
  if (options_.name.empty()) options_.name = ProgramOf(client_.sender());
  if (options_.period < 1 || options_.period > kMaxPeriod)
    throw LockStepError(options_.name,
                        "period " + std::to_string(options_.period) +
                            " is out of range [1, 1000000] steps",
                        -1);
  Join();
  client_.EnterLockStep(options_.name, first_tick_);
  if (options_.resume) ResumeIfPaused();
}

LockStep::~LockStep() {
  try {
    sync_t leave{};
    leave.controller = options_.name;
    leave.action = sync_t::ACTION_LEAVE;
    leave.token = token_;
    client_.PublishSync(leave);
  } catch (...) {
    // Leaving is a courtesy: the sim releases a silent controller anyway.
  }
  client_.LeaveLockStep();
}

void LockStep::Join() {
  sync_t join{};
  join.controller = options_.name;
  join.action = sync_t::ACTION_JOIN;
  join.period = options_.period;
  join_nonce_ = RandomToken();
  join.token = join_nonce_;
  const Clock::time_point deadline = Clock::now() + Seconds(options_.timeout);
  while (Clock::now() < deadline) {
    client_.PublishSync(join);
    const Clock::time_point again = std::min(deadline, Clock::now() + kJoinAgain);
    while (Clock::now() < again) {
      if (auto reply = client_.TakeSyncReply(options_.name)) {
        if (!AboutOwnMark(*reply)) continue;
        if (reply->event == sync_reply_t::EVENT_JOINED) {
          first_tick_ = reply->tick;
          token_ = reply->token;
          return;
        }
        if (reply->event == sync_reply_t::EVENT_REFUSED)
          throw LockStepError(options_.name, "the sim refused the join: " + reply->reason, -1);
        continue;  // news of an earlier controller of this name
      }
      client_.WaitForStepOrSyncReply(std::numeric_limits<int64_t>::max(), kPoll);
    }
  }
  throw Timeout("SIM_SYNC_REPLY to the JOIN of lock-step controller '" + options_.name + "'",
                options_.timeout, client_.url(), client_.SigningHint());
}

void LockStep::ResumeIfPaused() {
  // The join changed the sim's status, which it publishes at once.
  std::optional<status_t> status = client_.LatestStatus();
  if (!status) status = client_.WaitForStatus(std::min(options_.timeout, 2.0));
  if (status->run_state == status_t::RUN_PAUSED) client_.Resume();
}

const state_t& LockStep::Next() {
  int64_t next = first_tick_;
  if (tick_ >= 0) {
    next = tick_ + options_.period;
    SendAnswer(next);
  }
  state_ = AwaitTick(next);
  CheckPreviousReplies();
  tick_ = next;
  return state_;
}

void LockStep::SendAnswer(int64_t next_tick) {
  answer_ = sync_t{};
  answer_.controller = options_.name;
  answer_.action = sync_t::ACTION_DONE;
  answer_.tick = tick_;
  answer_.token = token_;
  answer_.commands = client_.TakeLockStepCommands(next_tick);
  answered_.clear();
  for (const command_t& c : answer_.commands) answered_.push_back(c.request_id);
  client_.PublishSync(answer_);
}

state_t LockStep::AwaitTick(int64_t tick) {
  const Clock::time_point start = Clock::now();
  const Clock::time_point deadline = start + Seconds(options_.timeout);
  // A tick legitimately takes period steps at the sim's speed.
  Clock::duration expected{};
  if (const auto status = client_.LatestStatus(); status && status->target_speed > 0)
    if (const auto catalog = client_.catalog())
      expected = Seconds(options_.period * catalog->step_size() / status->target_speed);
  Clock::time_point next_request = start + expected + kStateLate;
  for (;;) {
    if (const auto state = client_.WaitForStepOrSyncReply(tick, kPoll)) {
      if (state->step == tick) return *state;
      CheckSyncReplies(tick);
      throw LockStepError(options_.name,
                          "the sim passed tick " + std::to_string(tick) + " (it is at step " +
                              std::to_string(state->step) + ") without this controller's answer",
                          tick);
    }
    CheckSyncReplies(tick);
    if (const auto status = client_.LatestStatus();
        status && status->run_state == status_t::RUN_STOPPED &&
        status->simulation_id == client_.catalog()->simulation_id())
      throw SimStopped(status->step);
    const Clock::time_point now = Clock::now();
    if (now >= deadline)
      throw Timeout("SIM_STATE of lock-step tick " + std::to_string(tick) + " for controller '" +
                        options_.name + "'",
                    options_.timeout, client_.url());
    if (now >= next_request) {
      // The tick's state or this controller's answer may have been lost.
      // The sim answers a state request with the state of the step it is
      // at: this tick if it waits for us, the previous one if it still
      // waits for an answer (ours lost, or another controller's late).
      const auto latest = client_.LatestState();
      if (latest && answer_.action == sync_t::ACTION_DONE && latest->step == answer_.tick) {
        client_.PublishSync(answer_);  // refused as a duplicate if it was not lost
        ++resends_;
      }
      client_.PublishStateRequest();
      ++resends_;
      next_request = now + kStateAgain;
    }
  }
}

bool LockStep::AboutOwnMark(const sync_reply_t& reply) const {
  // A JOINED names no mark of ours; the rest echo the token of the mark
  // they answer, so that a mark forged in this controller's name (refused
  // for lack of the token) is not taken for its own.
  if (reply.event == sync_reply_t::EVENT_JOINED) return token_.empty();
  return SameToken(reply.token, token_.empty() ? join_nonce_ : token_);
}

void LockStep::CheckSyncReplies(int64_t tick) {
  while (auto reply = client_.TakeSyncReply(options_.name)) {
    if (!AboutOwnMark(*reply)) continue;
    if (reply->event == sync_reply_t::EVENT_RELEASED)
      throw LockStepError(options_.name,
                          "released by the sim at tick " + std::to_string(reply->tick) + ": " +
                              reply->reason,
                          reply->tick);
    // Our own answer sent again, when the first had arrived after all.
    const bool duplicate = reply->reason.rfind("duplicate done mark", 0) == 0;
    if (reply->event == sync_reply_t::EVENT_REFUSED && !duplicate)
      throw LockStepError(options_.name,
                          "the sim refused its answer while it waited for tick " +
                              std::to_string(tick) + ": " + reply->reason,
                          reply->tick);
  }
}

void LockStep::CheckPreviousReplies() {
  // The sim publishes the replies of a step before its state: they are in.
  for (const int64_t id : answered_) {
    const auto reply = client_.TakeReply(id);
    if (reply && !reply->accepted)
      throw Refused(reply->target.empty() ? "request " + std::to_string(id) : reply->target,
                    reply->reason, id);
  }
  answered_.clear();
}

}  // namespace simpartner::client
