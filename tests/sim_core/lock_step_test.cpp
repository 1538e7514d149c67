// The sim's bookkeeping of synchronous controllers (lock_step.h): which
// steps are whose ticks, which marks are taken and which refused (and
// why), and the order the answers apply in.
#include <gtest/gtest.h>

#include "simpartner/sim/lock_step.h"

namespace simpartner::sim {
namespace {

sync_t Join(const std::string& name, int64_t period, const std::string& sender = "ctl@host:1") {
  sync_t m{};
  m.controller = name;
  m.sender = sender;
  m.action = sync_t::ACTION_JOIN;
  m.period = period;
  return m;
}

sync_t Leave(const std::string& name) {
  sync_t m = Join(name, 1);
  m.action = sync_t::ACTION_LEAVE;
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

std::string Refusal(LockStep& lock_step, const sync_t& message, int64_t step) {
  const LockStep::Outcome outcome = lock_step.Handle(message, step);
  EXPECT_TRUE(outcome.refused);
  EXPECT_TRUE(outcome.reply.has_value());
  return outcome.reply ? outcome.reply->reason : "";
}

TEST(LockStepTest, TheFirstTickIsTheNextMultipleOfThePeriodFromTheCurrentStep) {
  LockStep lock_step;
  auto joined = lock_step.Handle(Join("a", 10), 0).reply;
  ASSERT_TRUE(joined);
  EXPECT_EQ(joined->event, sync_reply_t::EVENT_JOINED);
  EXPECT_EQ(joined->tick, 0);  // a sim paused at step 0: the controller decides step 1 on
  EXPECT_EQ(lock_step.Handle(Join("b", 10, "b@h:2"), 23).reply->tick, 30);
  EXPECT_EQ(lock_step.Handle(Join("c", 7, "c@h:3"), 21).reply->tick, 21);
  EXPECT_TRUE(lock_step.IsTick(30));
  EXPECT_TRUE(lock_step.IsTick(21));   // c's (a's ticks are 0, 10, 20, 30)
  EXPECT_FALSE(lock_step.IsTick(22));
  EXPECT_EQ(lock_step.WaitingOn(20), std::vector<std::string>{"a"});  // b starts at 30
  EXPECT_EQ(lock_step.WaitingOn(70), (std::vector<std::string>{"a", "b", "c"}));
}

TEST(LockStepTest, AnswersApplyInTheStepAfterTheTickInTheOrderOfTheNames) {
  LockStep lock_step;
  lock_step.Handle(Join("zeta", 1, "z@h:1"), 5);
  lock_step.Handle(Join("alpha", 1, "a@h:2"), 5);
  EXPECT_EQ(lock_step.WaitingOn(5), (std::vector<std::string>{"alpha", "zeta"}));
  // zeta answers first on the wire; alpha's commands still go first.
  EXPECT_FALSE(lock_step.Handle(Done("zeta", 5, {"Z1"}, "z@h:1"), 5).refused);
  EXPECT_EQ(lock_step.WaitingOn(5), std::vector<std::string>{"alpha"});
  EXPECT_FALSE(lock_step.Handle(Done("alpha", 5, {"A1", "A2"}, "a@h:2"), 5).refused);
  EXPECT_TRUE(lock_step.WaitingOn(5).empty());
  const std::vector<command_t> answers = lock_step.TakeAnswers(5);
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers[0].target, "A1");
  EXPECT_EQ(answers[1].target, "A2");
  EXPECT_EQ(answers[2].target, "Z1");
  for (const command_t& c : answers) EXPECT_EQ(c.apply_at_step, 5);  // in the step 5 -> 6
  EXPECT_TRUE(lock_step.TakeAnswers(5).empty());  // once only
}

TEST(LockStepTest, MarksForOtherTicksAreRefusedNamingTheTick) {
  LockStep lock_step;
  lock_step.Handle(Join("a", 10), 0);
  EXPECT_EQ(Refusal(lock_step, Done("a", 20), 10),
            "done mark of 'a' for tick 20, which has not happened (the sim is at step 10)");
  EXPECT_EQ(Refusal(lock_step, Done("a", 3), 10),
            "done mark of 'a' for tick 3, which has passed (the sim is at step 10)");
  EXPECT_EQ(Refusal(lock_step, Done("a", 15), 15),
            "done mark of 'a' for step 15, which is not one of its ticks (every 10 steps from 0)");
  EXPECT_FALSE(lock_step.Handle(Done("a", 10), 10).refused);
  EXPECT_EQ(Refusal(lock_step, Done("a", 10), 10), "duplicate done mark of 'a' for tick 10");
  lock_step.TakeAnswers(10);
  EXPECT_EQ(Refusal(lock_step, Done("a", 10), 11), "duplicate done mark of 'a' for tick 10");
  // A refused mark changes nothing: a is still awaited at its next tick.
  EXPECT_EQ(lock_step.WaitingOn(20), std::vector<std::string>{"a"});
}

TEST(LockStepTest, OnlyTheJoiningProcessSpeaksForAController) {
  LockStep lock_step;
  lock_step.Handle(Join("a", 1, "one@h:1"), 0);
  EXPECT_EQ(Refusal(lock_step, Done("a", 0, {}, "two@h:2"), 0),
            "done mark of 'a' from 'two@h:2'; it joined from 'one@h:1'");
  EXPECT_EQ(Refusal(lock_step, Join("a", 1, "two@h:2"), 0),
            "controller name 'a' is in use by 'one@h:1' (period 1)");
  EXPECT_EQ(Refusal(lock_step, Done("b", 0), 0), "done mark of 'b' for tick 0: it has not joined");
  // The same process joining again (its JOINED lost) gets the same answer.
  const auto again = lock_step.Handle(Join("a", 1, "one@h:1"), 0);
  EXPECT_FALSE(again.refused);
  EXPECT_EQ(again.reply->event, sync_reply_t::EVENT_JOINED);
  EXPECT_EQ(lock_step.size(), 1u);
}

TEST(LockStepTest, BadJoinsAreRefused) {
  LockStep lock_step;
  EXPECT_EQ(Refusal(lock_step, Join("a", 0), 0),
            "period 0 of 'a' is out of range [1, 1000000] steps");
  EXPECT_EQ(Refusal(lock_step, Join("", 1), 0), "a JOIN needs a controller name");
  sync_t odd = Join("a", 1);
  odd.action = 9;
  EXPECT_EQ(Refusal(lock_step, odd, 0), "unknown action 9 from 'ctl@host:1'");
  EXPECT_EQ(lock_step.size(), 0u);
}

TEST(LockStepTest, AReleasedControllerIsNoLongerWaitedOnAndToldWhy) {
  LockStep lock_step;
  lock_step.Handle(Join("slow", 1, "s@h:1"), 0);
  lock_step.Handle(Join("quick", 1, "q@h:2"), 0);
  lock_step.Handle(Done("quick", 4, {}, "q@h:2"), 4);
  const std::vector<sync_reply_t> released = lock_step.ReleaseWaiting(4, "no answer");
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].controller, "slow");
  EXPECT_EQ(released[0].event, sync_reply_t::EVENT_RELEASED);
  EXPECT_EQ(released[0].tick, 4);
  EXPECT_TRUE(lock_step.WaitingOn(4).empty());
  EXPECT_EQ(Refusal(lock_step, Done("slow", 4, {}, "s@h:1"), 4),
            "done mark of 'slow' for tick 4: released at tick 4 (no answer in time); join again");
  // Joining again makes it synchronous from the next tick on.
  EXPECT_EQ(lock_step.Handle(Join("slow", 1, "s@h:1"), 5).reply->tick, 5);
}

TEST(LockStepTest, LeavingStopsTheWait) {
  LockStep lock_step;
  lock_step.Handle(Join("a", 2), 0);
  lock_step.Handle(Done("a", 0), 0);
  lock_step.TakeAnswers(0);
  const auto left = lock_step.Handle(Leave("a"), 2);
  ASSERT_FALSE(left.refused);
  EXPECT_EQ(left.reply->event, sync_reply_t::EVENT_LEFT);
  EXPECT_EQ(left.reply->tick, 0);  // the last tick it answered
  EXPECT_TRUE(lock_step.WaitingOn(2).empty());
}

}  // namespace
}  // namespace simpartner::sim
