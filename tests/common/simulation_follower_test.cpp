// SimulationFollower (common/simulation_follower.h): which SIM_MODEL starts
// the followed simulation, and which is another simulation on the bus.
#include "simpartner/simulation_follower.h"

#include <gtest/gtest.h>

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

TEST_F(SimulationFollowerTest, TheFirstModelIsFollowedAndAResetOfItsSenderToo) {
  EXPECT_EQ(follower_.OnModel(5, "sim@a:1", At(0)), Verdict::kFollow);
  EXPECT_EQ(follower_.OnModel(5, "sim@a:1", At(10)), Verdict::kKnown);
  EXPECT_EQ(follower_.OnModel(6, "sim@a:1", At(20)), Verdict::kFollow);  // a reset
  EXPECT_EQ(follower_.followed(), 6);
  EXPECT_TRUE(follower_.WasFollowed(5));
  EXPECT_EQ(follower_.OnModel(5, "sim@a:1", At(30)), Verdict::kKnown);  // late, still its own
}

TEST_F(SimulationFollowerTest, AnotherSenderIsAnotherSimulationWhileTheFollowedOneTalks) {
  follower_.OnModel(5, "sim@a:1", At(0));
  follower_.Heard(5, At(2000));
  EXPECT_EQ(follower_.OnModel(9, "forger@b:2", At(2100)), Verdict::kOther);
  EXPECT_TRUE(follower_.IsOther(9));
  EXPECT_EQ(follower_.followed(), 5);
  follower_.Heard(9, At(2200));
  EXPECT_EQ(follower_.TakeSuccessor(At(3000)), std::nullopt);  // 5 heard 1 s ago
  // A sim heard the whole time is never replaced.
  for (int t = 2500; t < 20000; t += 1000) follower_.Heard(5, At(t));
  EXPECT_EQ(follower_.TakeSuccessor(At(20000)), std::nullopt);
}

TEST_F(SimulationFollowerTest, ASilentOrStoppedSimIsSucceededByTheNewestOther) {
  follower_.OnModel(5, "sim@a:1", At(0));
  follower_.OnModel(7, "sim@a:2", At(100));  // the restarted sim, before 5 is silent
  follower_.OnModel(8, "sim@c:3", At(200));
  follower_.Heard(7, At(3000));
  follower_.Heard(8, At(2000));
  EXPECT_EQ(follower_.TakeSuccessor(At(3100)), std::optional<int64_t>(7));
  EXPECT_EQ(follower_.followed(), 7);
  EXPECT_FALSE(follower_.IsOther(7));
  // Stopped: the next one at once, a new model too.
  follower_.Ended(7);
  EXPECT_EQ(follower_.OnModel(10, "sim@d:4", At(3200)), Verdict::kFollow);
}

TEST_F(SimulationFollowerTest, ForgedIdsWithoutEndAreRememberedBoundedly) {
  follower_.OnModel(5, "sim@a:1", At(0));
  for (int64_t id = 100; id < 100 + 10000; ++id)
    EXPECT_EQ(follower_.OnModel(id, "forger", At(1)), Verdict::kOther);
  size_t remembered = 0;
  for (int64_t id = 100; id < 100 + 10000; ++id) remembered += follower_.IsOther(id) ? 1 : 0;
  EXPECT_EQ(remembered, SimulationFollower::kMaxOthers);
  EXPECT_EQ(follower_.followed(), 5);
}

// A client that heard a SIM_STATUS first is attached to its simulation:
// another sim's model is another simulation, the attached one's model
// names its sender, and a reset from that sender is followed.
TEST_F(SimulationFollowerTest, AnAttachedSimulationIsFollowedBeforeItsModel) {
  follower_.Attach(5, At(0));
  EXPECT_EQ(follower_.followed(), 5);
  EXPECT_EQ(follower_.OnModel(9, "sim@b:2", At(100)), Verdict::kOther);
  EXPECT_EQ(follower_.OnModel(6, "", At(150)), Verdict::kOther);  // no sender is no match
  EXPECT_EQ(follower_.OnModel(5, "sim@a:1", At(200)), Verdict::kKnown);
  EXPECT_EQ(follower_.OnModel(7, "sim@a:1", At(300)), Verdict::kFollow);  // its reset
  EXPECT_EQ(follower_.followed(), 7);
}

}  // namespace
}  // namespace simpartner
