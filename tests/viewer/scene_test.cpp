// The viewer's bookkeeping of model and state, without GL or LCM: which
// messages it keeps, which it ignores (counted, described with channel,
// field and value), and how it follows a restarted simulation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "simpartner/viewer/scene.h"
#include "simpartner/status_t.hpp"
#include "viewer_messages.h"

namespace simpartner::viewer {
namespace {

using testing::ScanFor;
using testing::StateFor;
using testing::TwoBodyModel;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(SceneTest, BeforeAnyStateBodiesStandAtTheModelsInitialPoses) {
  Scene scene;
  EXPECT_FALSE(scene.has_model());
  ASSERT_TRUE(scene.OfferModel(TwoBodyModel(7)).accepted);
  EXPECT_EQ(scene.simulation_id(), 7);
  EXPECT_FALSE(scene.has_state());
  EXPECT_TRUE(scene.BodyPose(1).translation().isApprox(Eigen::Vector3d(2, 1, 0)));
  EXPECT_TRUE(scene.BodyPose(0).linear().isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(scene.Up().isApprox(Eigen::Vector3d::UnitY()));
}

TEST(SceneTest, KeepsOnlyTheNewestStateAndItsPoses) {
  Scene scene;
  const model_t m = TwoBodyModel(7);
  scene.OfferModel(m);
  for (int step = 1; step <= 5; ++step) {
    state_t s = StateFor(m, step);
    s.bodies[1].position[0] = 10.0 * step;
    // 90 degrees about z.
    s.bodies[1].orientation[0] = std::sqrt(0.5);
    s.bodies[1].orientation[3] = std::sqrt(0.5);
    ASSERT_TRUE(scene.OfferState(std::move(s)).accepted);
  }
  EXPECT_EQ(scene.state()->step, 5);
  EXPECT_EQ(scene.states_accepted(), 5);
  const Eigen::Isometry3d pose = scene.BodyPose(1);
  EXPECT_NEAR(pose.translation().x(), 50.0, 1e-12);
  // Body x turned onto world y.
  EXPECT_TRUE((pose.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(scene.rejected_total(), 0);
}

TEST(SceneTest, StatesBeforeTheModelAskForItWithoutCountingAsProblems) {
  Scene scene;
  const Verdict v = scene.OfferState(StateFor(TwoBodyModel(7), 1));
  EXPECT_FALSE(v.accepted);
  EXPECT_TRUE(v.want_model);
  EXPECT_FALSE(v.problem.has_value());
  EXPECT_EQ(scene.states_before_model(), 1);
  EXPECT_EQ(scene.rejected_total(), 0);
}

TEST(SceneTest, StateOfAnotherSimulationIsIgnoredAndAsksForTheModel) {
  Scene scene;
  const model_t m = TwoBodyModel(7);
  scene.OfferModel(m);
  scene.OfferState(StateFor(m, 1));
  state_t other = StateFor(m, 99);
  other.simulation_id = 8;
  const Verdict v = scene.OfferState(std::move(other));
  EXPECT_FALSE(v.accepted);
  EXPECT_TRUE(v.want_model);
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_EQ(v.problem->kind, Rejection::kOtherSimulation);
  EXPECT_NE(v.problem->message.find("SIM_STATE: simulation_id = 8"), std::string::npos)
      << v.problem->message;
  EXPECT_EQ(scene.state()->step, 1);  // the good one stays
  EXPECT_EQ(scene.rejected(Rejection::kOtherSimulation), 1);
}

TEST(SceneTest, StateWithMoreBodiesOrJointsThanTheModelIsIgnored) {
  Scene scene;
  const model_t m = TwoBodyModel(7);
  scene.OfferModel(m);
  state_t more = StateFor(m, 1);
  more.bodies.resize(5);
  more.num_bodies = 5;
  Verdict v = scene.OfferState(std::move(more));
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_EQ(v.problem->kind, Rejection::kBodyCount);
  EXPECT_NE(v.problem->message.find("num_bodies = 5"), std::string::npos) << v.problem->message;
  EXPECT_NE(v.problem->message.find("the model of simulation 7 has 2"), std::string::npos)
      << v.problem->message;

  state_t fewer_joints = StateFor(m, 2);
  fewer_joints.joints.clear();
  fewer_joints.num_joints = 0;
  v = scene.OfferState(std::move(fewer_joints));
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_EQ(v.problem->kind, Rejection::kJointCount);
  EXPECT_NE(v.problem->message.find("num_joints = 0"), std::string::npos) << v.problem->message;
  EXPECT_FALSE(scene.has_state());
  EXPECT_EQ(scene.RejectionSummary(), "1 body count, 1 joint count");
}

TEST(SceneTest, NonFinitePosesAndBrokenQuaternionsAreIgnoredNamingBodyAndField) {
  Scene scene;
  const model_t m = TwoBodyModel(7);
  scene.OfferModel(m);
  scene.OfferState(StateFor(m, 1));

  state_t nan_position = StateFor(m, 2);
  nan_position.bodies[1].position[2] = kNaN;
  Verdict v = scene.OfferState(std::move(nan_position));
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_EQ(v.problem->kind, Rejection::kNonFinite);
  EXPECT_NE(v.problem->message.find("bodies[1].position[2] = nan (body 'Ball', step 2)"),
            std::string::npos)
      << v.problem->message;

  state_t inf_orientation = StateFor(m, 3);
  inf_orientation.bodies[0].orientation[1] = INFINITY;
  v = scene.OfferState(std::move(inf_orientation));
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_NE(v.problem->message.find("bodies[0].orientation[1] = inf"), std::string::npos)
      << v.problem->message;

  state_t zero_quaternion = StateFor(m, 4);
  zero_quaternion.bodies[0].orientation[0] = 0;
  v = scene.OfferState(std::move(zero_quaternion));
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_EQ(v.problem->kind, Rejection::kBadQuaternion);
  EXPECT_NE(v.problem->message.find("orientation has length 0"), std::string::npos)
      << v.problem->message;

  state_t nan_force = StateFor(m, 5);
  nan_force.joints[0].force1[1] = kNaN;
  v = scene.OfferState(std::move(nan_force));
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_NE(v.problem->message.find("joints[0].force1[1] = nan (joint 'Swing'"), std::string::npos)
      << v.problem->message;

  // The last good state is still what is drawn.
  EXPECT_EQ(scene.state()->step, 1);
  EXPECT_TRUE(scene.BodyPose(1).translation().allFinite());
  EXPECT_EQ(scene.rejected(Rejection::kNonFinite), 3);
  EXPECT_EQ(scene.rejected(Rejection::kBadQuaternion), 1);
}

TEST(SceneTest, ANewSimulationReplacesModelStateAndScans) {
  Scene scene;
  const model_t first = TwoBodyModel(7);
  scene.OfferModel(first);
  scene.OfferState(StateFor(first, 100));
  scene.OfferSensorReading(ScanFor(first, {1, 2, 3}));
  const int64_t generation = scene.model_generation();

  // The periodic re-announcement keeps everything.
  scene.OfferModel(first);
  EXPECT_EQ(scene.model_generation(), generation);
  EXPECT_TRUE(scene.has_state());
  EXPECT_EQ(scene.scans().size(), 1u);

  // A reset: the old simulation's last status says so, then the new
  // model comes.
  status_t reset{};
  reset.simulation_id = 7;
  reset.run_state = status_t::RUN_RESET;
  scene.OfferStatus(reset);
  model_t second = TwoBodyModel(8);
  second.bodies[1].initial_position[0] = -3;
  ASSERT_TRUE(scene.OfferModel(second).accepted);
  EXPECT_GT(scene.model_generation(), generation);
  EXPECT_FALSE(scene.has_state());
  EXPECT_TRUE(scene.scans().empty());
  EXPECT_NEAR(scene.BodyPose(1).translation().x(), -3, 1e-12);
  // States of the old simulation no longer fit.
  EXPECT_EQ(scene.OfferState(StateFor(first, 101)).problem->kind, Rejection::kOtherSimulation);
}

TEST(SceneTest, ModelsThatCannotBeDrawnAreRefusedWithTheField) {
  struct Case {
    const char* what;
    void (*damage)(model_t*);
    const char* expect;
  };
  const Case cases[] = {
      {"negative box size", [](model_t* m) { m->bodies[0].geometry.size[1] = -2; },
       "bodies[0].geometry.size[1] = -2 (above 0 to 100000 m) (body 'Base')"},
      {"NaN sphere radius", [](model_t* m) { m->bodies[1].geometry.size[0] = kNaN; },
       "bodies[1].geometry.size[0] = nan (body 'Ball')"},
      {"unknown kind", [](model_t* m) { m->bodies[1].geometry.kind = 42; },
       "bodies[1].geometry.kind = 42"},
      {"joint to a missing body", [](model_t* m) { m->joints[0].body1 = 9; },
       "joints[0].body1 = 9 (no such body), the model has 2 (joint 'Swing')"},
      {"sensor on a missing body", [](model_t* m) { m->sensors[0].body = 2; },
       "sensors[0].body = 2 (no such body), the model has 2"},
      {"samples do not match rows x columns",
       [](model_t* m) {
         m->heightfield.present = true;
         m->heightfield.rows = 3;
         m->heightfield.columns = 4;
         m->heightfield.width = m->heightfield.depth = 1;
         m->heightfield.scale = 1;
         m->heightfield.samples.assign(11, 0.0f);
         m->heightfield.num_samples = 11;
       },
       "heightfield.num_samples = 11 but rows x columns = 12"},
      {"zero up", [](model_t* m) { m->up[1] = 0; }, "up = (0, 0, 0) is not a unit vector"},
  };
  for (const Case& c : cases) {
    Scene scene;
    model_t m = TwoBodyModel(7);
    c.damage(&m);
    const Verdict v = scene.OfferModel(m);
    EXPECT_FALSE(v.accepted) << c.what;
    ASSERT_TRUE(v.problem.has_value()) << c.what;
    EXPECT_EQ(v.problem->kind, Rejection::kBadModel) << c.what;
    EXPECT_NE(v.problem->message.find(std::string("SIM_MODEL: ") + c.expect), std::string::npos)
        << c.what << ": " << v.problem->message;
    EXPECT_FALSE(scene.has_model()) << c.what;
  }
}

TEST(SceneTest, ScannerReadingsAreKeptPerSensorAndBadOnesCounted) {
  Scene scene;
  const model_t m = TwoBodyModel(7);
  scene.OfferModel(m);
  EXPECT_TRUE(scene.OfferSensorReading(ScanFor(m, {4, 5, 6})).accepted);
  EXPECT_TRUE(scene.OfferSensorReading(ScanFor(m, {1, 2, 3})).accepted);
  ASSERT_EQ(scene.scans().size(), 1u);
  EXPECT_EQ(scene.scans().at(0).values[0], 1);

  sensor_reading_t unknown = ScanFor(m, {1});
  unknown.sensor = 3;
  Verdict v = scene.OfferSensorReading(unknown);
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_NE(v.problem->message.find(
                "SIM_SENSOR: sensor = 3 but the model of simulation 7 has 1 sensors"),
            std::string::npos)
      << v.problem->message;
  sensor_reading_t nan_range = ScanFor(m, {1, kNaN});
  v = scene.OfferSensorReading(nan_range);
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_NE(v.problem->message.find("values[1] = nan"), std::string::npos) << v.problem->message;
  EXPECT_EQ(scene.scans().at(0).values[0], 1);
}

TEST(SceneTest, StatusOfAnotherSimulationAsksForTheModel) {
  Scene scene;
  scene.OfferModel(TwoBodyModel(7));
  status_t status{};
  status.simulation_id = 7;
  status.run_state = status_t::RUN_PAUSED;
  EXPECT_FALSE(scene.OfferStatus(status).want_model);
  ASSERT_NE(scene.status(), nullptr);
  status.simulation_id = 9;
  EXPECT_TRUE(scene.OfferStatus(status).want_model);
  EXPECT_EQ(scene.status()->simulation_id, 7);
}

TEST(SceneTest, FocusAndFollowUseRobotZero) {
  Scene scene;
  const model_t m = TwoBodyModel(7);
  scene.OfferModel(m);
  // Base centre (0, 1, 0), Ball (2, 1, 0).
  EXPECT_TRUE(scene.FollowPoint()->isApprox(Eigen::Vector3d(1, 1, 0)));
  const auto [centre, radius] = scene.FocusSphere();
  // Between the two bodies, and wide enough for both: the box reaches
  // sqrt(0.5^2 + 1^2 + 0.5^2) from its centre, the ball 0.25.
  EXPECT_GT(centre.x(), 0);
  EXPECT_LT(centre.x(), 2);
  EXPECT_GE(radius, (2.25 + std::sqrt(1.5)) / 2 - 1e-9);
  state_t s = StateFor(m, 1);
  s.bodies[0].position[2] = 4;
  s.bodies[1].position[2] = 4;
  scene.OfferState(std::move(s));
  EXPECT_NEAR(scene.FollowPoint()->z(), 4, 1e-12);
}

TEST(SceneTest, WithoutRobotsTheCameraFollowsWhatMoves) {
  Scene scene;
  model_t m = TwoBodyModel(7);
  m.robots.clear();
  m.num_robots = 0;
  for (body_t& b : m.bodies) b.robot = -1;
  for (joint_t& j : m.joints) j.robot = -1;
  for (sensor_t& s : m.sensors) s.robot = -1;
  m.bodies[0].is_static = true;  // the box stays, the ball moves
  scene.OfferModel(m);
  EXPECT_TRUE(scene.FollowPoint()->isApprox(Eigen::Vector3d(2, 1, 0)));
  // Framing still takes in every body.
  EXPECT_LT(scene.FocusSphere().first.x(), 2);
  m.bodies[1].is_static = true;
  Scene fixed;
  fixed.OfferModel(m);
  EXPECT_FALSE(fixed.FollowPoint().has_value());
}

TEST(SceneTest, UndecodableMessagesAreCountedPerChannel) {
  Scene scene;
  scene.CountUndecodable("SIM_STATE", "17 bytes refused as simpartner.state_t: too short");
  EXPECT_EQ(scene.rejected(Rejection::kUndecodable), 1);
  EXPECT_EQ(scene.recent_problems().back().message,
            "SIM_STATE: 17 bytes refused as simpartner.state_t: too short; ignored");
}

}  // namespace
}  // namespace simpartner::viewer
