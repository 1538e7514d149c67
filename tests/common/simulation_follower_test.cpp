// SimulationFollower (common/simulation_follower.h): which SIM_MODEL starts
// the followed simulation, and which is another simulation on the bus.
#include "simpartner/simulation_follower.h"

#include <gtest/gtest.h>

#include "simpartner/status_t.hpp"

namespace simpartner {
namespace {

using Verdict = SimulationFollower::Verdict;
using std::chrono::milliseconds;

class SimulationFollowerTest : public ::testing::Test {
 protected:
  SimulationFollower follower_{milliseconds(2500)};
  SimulationFollower::Clock::time_point t0_ = SimulationFollower::Clock::now();
  SimulationFollower::Clock::time_point At(int ms) const { return t0_ + milliseconds(ms); }
};

// A new id while the followed simulation still talks is another
// simulation, even a copy of its own model with its sender (the audit's
// copied model: the sender is text anyone can write); once it says it
// was reset (RUN_RESET), the next model is its successor.
TEST_F(SimulationFollowerTest, TheFirstModelIsFollowedAndAResetOnceItsSimSaysSo) {
  EXPECT_EQ(follower_.OnModel(5, At(0)), Verdict::kFollow);
  EXPECT_EQ(follower_.OnModel(5, At(10)), Verdict::kKnown);
  EXPECT_EQ(follower_.OnModel(6, At(20)), Verdict::kOther);  // a copy, or a reset not yet said
  EXPECT_EQ(follower_.followed(), 5);
  EXPECT_TRUE(EndsSimulation(status_t::RUN_RESET));
  follower_.Ended(5);  // its status said RUN_RESET
  EXPECT_EQ(follower_.OnModel(6, At(30)), Verdict::kFollow);
  EXPECT_EQ(follower_.followed(), 6);
  EXPECT_TRUE(follower_.WasFollowed(5));
  EXPECT_EQ(follower_.OnModel(5, At(40)), Verdict::kKnown);  // late, still its own
}

TEST(EndsSimulation, StoppedAndResetEndIt) {
  EXPECT_TRUE(EndsSimulation(status_t::RUN_STOPPED));
  EXPECT_TRUE(EndsSimulation(status_t::RUN_RESET));
  for (const int8_t other : {status_t::RUN_RUNNING, status_t::RUN_PAUSED, status_t::RUN_FAULTED})
    EXPECT_FALSE(EndsSimulation(other));
}

TEST_F(SimulationFollowerTest, AnotherSenderIsAnotherSimulationWhileTheFollowedOneTalks) {
  follower_.OnModel(5, At(0));
  follower_.Heard(5, At(2000));
  EXPECT_EQ(follower_.OnModel(9, At(2100)), Verdict::kOther);
  EXPECT_TRUE(follower_.IsOther(9));
  EXPECT_EQ(follower_.followed(), 5);
  follower_.Heard(9, At(2200));
  EXPECT_EQ(follower_.TakeSuccessor(At(3000)), std::nullopt);  // 5 heard 1 s ago
  // A sim heard the whole time is never replaced.
  for (int t = 2500; t < 20000; t += 1000) follower_.Heard(5, At(t));
  EXPECT_EQ(follower_.TakeSuccessor(At(20000)), std::nullopt);
}

TEST_F(SimulationFollowerTest, ASilentOrStoppedSimIsSucceededByTheNewestOther) {
  follower_.OnModel(5, At(0));
  follower_.OnModel(7, At(100));  // the restarted sim, before 5 is silent
  follower_.OnModel(8, At(200));
  follower_.Heard(7, At(3000));
  follower_.Heard(8, At(2000));
  EXPECT_EQ(follower_.TakeSuccessor(At(3100)), std::optional<int64_t>(7));
  EXPECT_EQ(follower_.followed(), 7);
  EXPECT_FALSE(follower_.IsOther(7));
  // Stopped: the next one at once, a new model too.
  follower_.Ended(7);
  EXPECT_EQ(follower_.OnModel(10, At(3200)), Verdict::kFollow);
}

// The audit's phantom: a copy heard once mid-run is not the successor of
// the followed simulation when it ends; only another heard within the
// silence is (a sim restarted at once).
TEST_F(SimulationFollowerTest, AnEndedSimIsNotSucceededByACopyHeardLongAgo) {
  follower_.OnModel(5, At(0));
  EXPECT_EQ(follower_.OnModel(9, At(100)), Verdict::kOther);  // a copy: no states behind it
  follower_.Heard(5, At(5000));
  follower_.Ended(5);
  EXPECT_EQ(follower_.TakeSuccessor(At(5100)), std::nullopt);
  EXPECT_EQ(follower_.followed(), 5);
  follower_.Heard(9, At(5200));  // it talks after all: a sim
  EXPECT_EQ(follower_.TakeSuccessor(At(5300)), std::optional<int64_t>(9));
}

TEST_F(SimulationFollowerTest, ForgedIdsWithoutEndAreRememberedBoundedly) {
  follower_.OnModel(5, At(0));
  for (int64_t id = 100; id < 100 + 10000; ++id)
    EXPECT_EQ(follower_.OnModel(id, At(1)), Verdict::kOther);
  size_t remembered = 0;
  for (int64_t id = 100; id < 100 + 10000; ++id) remembered += follower_.IsOther(id) ? 1 : 0;
  EXPECT_EQ(remembered, SimulationFollower::kMaxOthers);
  EXPECT_EQ(follower_.followed(), 5);
}

// A client that heard a SIM_STATUS first is attached to its simulation:
// another sim's model is another simulation, the attached one's model is
// known, and after it says it was reset the next model is followed.
TEST_F(SimulationFollowerTest, AnAttachedSimulationIsFollowedBeforeItsModel) {
  follower_.Attach(5, At(0));
  EXPECT_EQ(follower_.followed(), 5);
  EXPECT_EQ(follower_.OnModel(9, At(100)), Verdict::kOther);
  EXPECT_EQ(follower_.OnModel(5, At(200)), Verdict::kKnown);
  follower_.Ended(5);
  EXPECT_EQ(follower_.OnModel(7, At(300)), Verdict::kFollow);  // its reset
  EXPECT_EQ(follower_.followed(), 7);
}

}  // namespace
}  // namespace simpartner
