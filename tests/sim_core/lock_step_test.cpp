// The sim's bookkeeping of synchronous controllers (lock_step_.h): which
// steps are whose ticks, which marks are taken and which refused (and
// why), the order the answers apply in, and that only a controller itself
// acts for it.
#include <gtest/gtest.h>

#include <map>

#include "simpartner/sim/lock_step.h"

namespace simpartner::sim {
namespace {

sync_t Join(const std::string& name, int64_t period, const std::string& sender = "ctl@host:1") {
  sync_t m{};
  m.controller = name;
  m.sender = sender;
  m.action = sync_t::ACTION_JOIN;
  m.period = period;
  m.token = "nonce of " + name + " " + sender;  // the same when it asks again
  return m;
}

sync_t Leave(const std::string& name) {
  sync_t m = Join(name, 1);
  m.action = sync_t::ACTION_LEAVE;
  m.token.clear();  // the fixture gives it the controller's
  return m;
}

sync_t Done(const std::string& name, int64_t tick, std::vector<std::string> targets = {},
            const std::string& sender = "ctl@host:1") {
  sync_t m{};
  m.controller = name;
  m.sender = sender;
  m.action = sync_t::ACTION_DONE;
  m.tick = tick;
  for (const std::string& t : targets) {
    command_t c{};
    c.target = t;
    c.apply_at_step = -1;
    m.commands.push_back(c);
  }
  m.num_commands = static_cast<int32_t>(m.commands.size());
  return m;
}

// The table, and the tokens its JOINED replies gave: a controller's own
// marks carry its token, as the client's do (a mark with a token of its
// own is sent as it is).
class LockStepTest : public ::testing::Test {
 protected:
  LockStep::Outcome Handle(sync_t m, int64_t step, const LockStep::Origin& origin = {}) {
    if (m.action != sync_t::ACTION_JOIN && m.token.empty()) m.token = tokens_[m.controller];
    LockStep::Outcome outcome = lock_step_.Handle(m, step, origin);
    if (outcome.reply && outcome.reply->event == sync_reply_t::EVENT_JOINED)
      tokens_[m.controller] = outcome.reply->token;
    return outcome;
  }
  std::string Refusal(const sync_t& m, int64_t step, const LockStep::Origin& origin = {}) {
    const LockStep::Outcome outcome = Handle(m, step, origin);
    EXPECT_TRUE(outcome.refused);
    EXPECT_TRUE(outcome.reply.has_value());
    return outcome.reply ? outcome.reply->reason : "";
  }
  LockStep lock_step_;
  std::map<std::string, std::string> tokens_;
};

TEST_F(LockStepTest, TheFirstTickIsTheNextMultipleOfThePeriodFromTheCurrentStep) {
  auto joined = Handle(Join("a", 10), 0).reply;
  ASSERT_TRUE(joined);
  EXPECT_EQ(joined->event, sync_reply_t::EVENT_JOINED);
  EXPECT_EQ(joined->tick, 0);  // a sim paused at step 0: the controller decides step 1 on
  EXPECT_EQ(Handle(Join("b", 10, "b@h:2"), 23).reply->tick, 30);
  EXPECT_EQ(Handle(Join("c", 7, "c@h:3"), 21).reply->tick, 21);
  EXPECT_TRUE(lock_step_.IsTick(30));
  EXPECT_TRUE(lock_step_.IsTick(21));   // c's (a's ticks are 0, 10, 20, 30)
  EXPECT_FALSE(lock_step_.IsTick(22));
  EXPECT_EQ(lock_step_.WaitingOn(20), std::vector<std::string>{"a"});  // b starts at 30
  EXPECT_EQ(lock_step_.WaitingOn(70), (std::vector<std::string>{"a", "b", "c"}));
}

TEST_F(LockStepTest, AnswersApplyInTheStepAfterTheTickInTheOrderOfTheNames) {
  Handle(Join("zeta", 1, "z@h:1"), 5);
  Handle(Join("alpha", 1, "a@h:2"), 5);
  EXPECT_EQ(lock_step_.WaitingOn(5), (std::vector<std::string>{"alpha", "zeta"}));
  // zeta answers first on the wire; alpha's commands still go first.
  EXPECT_FALSE(Handle(Done("zeta", 5, {"Z1"}, "z@h:1"), 5).refused);
  EXPECT_EQ(lock_step_.WaitingOn(5), std::vector<std::string>{"alpha"});
  EXPECT_FALSE(Handle(Done("alpha", 5, {"A1", "A2"}, "a@h:2"), 5).refused);
  EXPECT_TRUE(lock_step_.WaitingOn(5).empty());
  const std::vector<command_t> answers = lock_step_.TakeAnswers(5);
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers[0].target, "A1");
  EXPECT_EQ(answers[1].target, "A2");
  EXPECT_EQ(answers[2].target, "Z1");
  for (const command_t& c : answers) EXPECT_EQ(c.apply_at_step, 5);  // in the step 5 -> 6
  EXPECT_TRUE(lock_step_.TakeAnswers(5).empty());  // once only
}

TEST_F(LockStepTest, MarksForOtherTicksAreRefusedNamingTheTick) {
  Handle(Join("a", 10), 0);
  EXPECT_EQ(Refusal(Done("a", 20), 10),
            "done mark of 'a' for tick 20, which has not happened (the sim is at step 10)");
  EXPECT_EQ(Refusal(Done("a", 3), 10),
            "done mark of 'a' for tick 3, which has passed (the sim is at step 10)");
  EXPECT_EQ(Refusal(Done("a", 15), 15),
            "done mark of 'a' for step 15, which is not one of its ticks (every 10 steps from 0)");
  EXPECT_FALSE(Handle(Done("a", 10), 10).refused);
  EXPECT_EQ(Refusal(Done("a", 10), 10), "duplicate done mark of 'a' for tick 10");
  lock_step_.TakeAnswers(10);
  EXPECT_EQ(Refusal(Done("a", 10), 11), "duplicate done mark of 'a' for tick 10");
  // A refused mark changes nothing: a is still awaited at its next tick.
  EXPECT_EQ(lock_step_.WaitingOn(20), std::vector<std::string>{"a"});
}

TEST_F(LockStepTest, OnlyTheJoiningProcessSpeaksForAController) {
  Handle(Join("a", 1, "one@h:1"), 0);
  EXPECT_EQ(Refusal(Done("a", 0, {}, "two@h:2"), 0),
            "done mark of 'a' from 'two@h:2'; it joined from 'one@h:1'");
  EXPECT_EQ(Refusal(Join("a", 1, "two@h:2"), 0),
            "controller name 'a' is in use by 'one@h:1' (period 1)");
  EXPECT_EQ(Refusal(Done("b", 0), 0), "done mark of 'b' for tick 0: it has not joined");
  // The same process joining again (its JOINED lost) gets the same answer.
  const auto again = Handle(Join("a", 1, "one@h:1"), 0);
  EXPECT_FALSE(again.refused);
  EXPECT_EQ(again.reply->event, sync_reply_t::EVENT_JOINED);
  EXPECT_EQ(lock_step_.size(), 1u);
}

TEST_F(LockStepTest, BadJoinsAreRefused) {
  EXPECT_EQ(Refusal(Join("a", 0), 0),
            "period 0 of 'a' is out of range [1, 1000000] steps");
  EXPECT_EQ(Refusal(Join("", 1), 0), "a JOIN needs a controller name");
  sync_t odd = Join("a", 1);
  odd.action = 9;
  EXPECT_EQ(Refusal(odd, 0), "unknown action 9 from 'ctl@host:1'");
  EXPECT_EQ(lock_step_.size(), 0u);
}

TEST_F(LockStepTest, AReleasedControllerIsNoLongerWaitedOnAndToldWhy) {
  Handle(Join("slow", 1, "s@h:1"), 0);
  Handle(Join("quick", 1, "q@h:2"), 0);
  Handle(Done("quick", 4, {}, "q@h:2"), 4);
  const std::vector<sync_reply_t> released = lock_step_.ReleaseWaiting(4, "no answer");
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].controller, "slow");
  EXPECT_EQ(released[0].event, sync_reply_t::EVENT_RELEASED);
  EXPECT_EQ(released[0].tick, 4);
  EXPECT_TRUE(lock_step_.WaitingOn(4).empty());
  EXPECT_EQ(Refusal(Done("slow", 4, {}, "s@h:1"), 4),
            "done mark of 'slow' for tick 4: released at tick 4 (no answer in time); join again");
  // Joining again, after the wait, makes it synchronous from the next tick on.
  LockStep::Origin later;
  later.now += LockStep::kRejoinWaitFirst;
  EXPECT_EQ(Handle(Join("slow", 1, "s@h:1"), 5, later).reply->tick, 5);
}

TEST_F(LockStepTest, LeavingStopsTheWait) {
  Handle(Join("a", 2), 0);
  Handle(Done("a", 0), 0);
  lock_step_.TakeAnswers(0);
  const auto left = Handle(Leave("a"), 2);
  ASSERT_FALSE(left.refused);
  EXPECT_EQ(left.reply->event, sync_reply_t::EVENT_LEFT);
  EXPECT_EQ(left.reply->tick, 0);  // the last tick it answered
  EXPECT_TRUE(lock_step_.WaitingOn(2).empty());
}

// The audit's: the controller's name and sender, which SIM_STATUS lists,
// once let any sender answer or leave for it. Its marks need the token its
// JOINED gave, and a JOIN repeated with another nonce does not get it.
TEST_F(LockStepTest, OnlyTheControllerItselfActsForIt) {
  const auto joined = Handle(Join("a", 1, "one@h:1"), 0);
  ASSERT_FALSE(joined.refused);
  const std::string token = joined.reply->token;
  EXPECT_EQ(token.size(), 32u);
  EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos) << token;
  EXPECT_NE(Handle(Join("b", 1, "two@h:2"), 0).reply->token, token);

  sync_t forged = Done("a", 0, {"Forged"}, "one@h:1");
  forged.token = "0123456789abcdef0123456789abcdef";
  EXPECT_EQ(Refusal(forged, 0),
            "done mark of 'a' without the token its JOINED gave: only the controller itself "
            "acts for it");
  // The refusal echoes the mark's token: the controller, seeing a refusal
  // in its name, knows it was not of its own mark.
  EXPECT_EQ(Handle(forged, 0).reply->token, forged.token);
  sync_t leave = Leave("a");
  leave.sender = "one@h:1";
  leave.token = "what a forger without it sends";
  EXPECT_EQ(Refusal(leave, 0),
            "LEAVE of 'a' without the token its JOINED gave: only the controller itself acts "
            "for it");
  sync_t copied = Join("a", 1, "one@h:1");
  copied.token = "a nonce of the forger's";
  EXPECT_EQ(Refusal(copied, 0), "controller name 'a' is in use by 'one@h:1' (period 1)");
  // Nothing changed: a is waited on, and its own answer is taken.
  EXPECT_EQ(lock_step_.WaitingOn(0), (std::vector<std::string>{"a", "b"}));
  EXPECT_FALSE(Handle(Done("a", 0, {"Own"}, "one@h:1"), 0).refused);
}

// On a signed bus the marks must also come from the JOIN's signing link:
// a reader of the bus who saw the token cannot sign as the controller.
TEST_F(LockStepTest, OnASignedBusMarksComeFromTheJoinsLink) {
  LockStep::Origin link7, link8;
  link7.link = 7;
  link8.link = 8;
  ASSERT_FALSE(Handle(Join("a", 1), 0, link7).refused);
  EXPECT_EQ(Refusal(Done("a", 0), 0, link8),
            "done mark of 'a' from another signing link than its JOIN's: only the controller "
            "itself acts for it");
  EXPECT_EQ(Refusal(Join("a", 1), 0, link8), "controller name 'a' is in use by 'ctl@host:1' (period 1)");
  EXPECT_FALSE(Handle(Done("a", 0), 0, link7).refused);
}

// The audit's controller that joins and never answers rejoined at once
// after each release: 20 steps in 20 s. Each release now doubles the wait
// before its name or its sender may join again; an answer forgives.
TEST_F(LockStepTest, RejoiningAfterAReleaseWaitsLongerEachTime) {
  const LockStep::Clock::time_point t0 = LockStep::Clock::now();
  auto at = [&](double seconds) {
    LockStep::Origin o;
    o.now = t0 + std::chrono::duration_cast<LockStep::Clock::duration>(
                     std::chrono::duration<double>(seconds));
    return o;
  };
  ASSERT_FALSE(Handle(Join("mute", 1, "m@h:1"), 0, at(0)).refused);
  ASSERT_EQ(lock_step_.ReleaseWaiting(0, "no answer", at(0).now).size(), 1u);
  EXPECT_EQ(Refusal(Join("mute", 1, "m@h:1"), 1, at(1)),
            "controller 'mute' was released 1 time for not answering (last at tick 0); it may "
            "join again in 4 s");
  EXPECT_EQ(Refusal(Join("other", 1, "m@h:1"), 1, at(1)),
            "sender 'm@h:1' was released 1 time for not answering (last at tick 0); it may "
            "join again in 4 s");
  ASSERT_FALSE(Handle(Join("mute", 1, "m@h:1"), 1, at(5)).refused);
  ASSERT_EQ(lock_step_.ReleaseWaiting(1, "no answer", at(10).now).size(), 1u);
  EXPECT_NE(Refusal(Join("mute", 1, "m@h:1"), 2, at(19)).find("released 2 times"),
            std::string::npos);
  ASSERT_FALSE(Handle(Join("mute", 1, "m@h:1"), 2, at(20)).refused);
  // It answers: forgiven, the next release waits the first wait again.
  ASSERT_FALSE(Handle(Done("mute", 2, {}, "m@h:1"), 2, at(20)).refused);
  lock_step_.TakeAnswers(2);
  ASSERT_EQ(lock_step_.ReleaseWaiting(3, "no answer", at(30).now).size(), 1u);
  EXPECT_NE(Refusal(Join("mute", 1, "m@h:1"), 4, at(31)).find("released 1 time "),
            std::string::npos);
  EXPECT_FALSE(Handle(Join("mute", 1, "m@h:1"), 4, at(35)).refused);
}

// The audit's 64 JOINs of one sender locked every honest controller out.
// A sender now holds at most kMaxControllersPerSender places.
TEST_F(LockStepTest, OneSenderCannotTakeEveryPlace) {
  for (size_t k = 0; k < LockStep::kMaxControllersPerSender; ++k)
    ASSERT_FALSE(Handle(Join("greedy" + std::to_string(k), 1000000, "g@h:1"), 0).refused) << k;
  EXPECT_EQ(Refusal(Join("greedy8", 1000000, "g@h:1"), 0),
            "sender 'g@h:1' has 8 synchronous controllers already (at most 8 a sender)");
  EXPECT_FALSE(Handle(Join("honest", 1, "h@h:2"), 0).refused);
}

}  // namespace
}  // namespace simpartner::sim
