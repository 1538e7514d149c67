// The follow camera looks past a wall: distances worked out by hand for a
// wall box placed between a robot and the eye.
#include <gtest/gtest.h>

#include <cmath>

#include "simpartner/viewer/line_of_sight.h"
#include "viewer_messages.h"

namespace simpartner::viewer {
namespace {

using testing::TwoBodyModel;

// TwoBodyModel's robot (Base at (0, 1, 0)) and a static wall: a box 0.2 m
// thick along x, 4 m high and 10 m wide, its near face at x = 3.
model_t ModelWithWall(bool is_static, double angle_about_y = 0) {
  model_t m = TwoBodyModel(7);
  body_t wall{};
  wall.id = m.num_bodies;
  wall.name = "Wall";
  wall.robot = -1;
  wall.is_static = is_static;
  wall.mass = is_static ? 0 : 10;
  wall.geometry.kind = geometry_t::KIND_BOX;
  wall.geometry.size[0] = 0.2;
  wall.geometry.size[1] = 4;
  wall.geometry.size[2] = 10;
  wall.initial_position[0] = 3.1;
  wall.initial_position[1] = 1;
  wall.initial_orientation[0] = std::cos(angle_about_y / 2);
  wall.initial_orientation[2] = std::sin(angle_about_y / 2);
  m.bodies.push_back(wall);
  ++m.num_bodies;
  return m;
}

// Eye 5 m along +x from the robot's base, level: the wall is in between.
Camera LevelCameraOnTheRobot() {
  Camera c;
  c.target = Eigen::Vector3d(0, 1, 0);
  c.yaw = 0;
  c.pitch = 0;
  c.distance = 5;
  return c;
}

TEST(LineOfSightTest, TheRayMeetsTheWallsNearFace) {
  Scene scene;
  ASSERT_TRUE(scene.OfferModel(ModelWithWall(true)).accepted);
  const auto hit = FirstWorldObjectHit(scene, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::UnitX(), 10);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 3.0, 1e-12);
  // Away from the wall, or not as far as it: nothing.
  EXPECT_FALSE(FirstWorldObjectHit(scene, Eigen::Vector3d(0, 1, 0), -Eigen::Vector3d::UnitX(), 10));
  EXPECT_FALSE(FirstWorldObjectHit(scene, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::UnitX(), 2.9));
  // Over its top (y = 3): nothing.
  EXPECT_FALSE(FirstWorldObjectHit(scene, Eigen::Vector3d(0, 3.5, 0), Eigen::Vector3d::UnitX(), 10));
}

TEST(LineOfSightTest, AWallTurnedThirtyDegreesIsMetFurther) {
  Scene scene;
  // Turned about y, the near face crosses the x axis at 3.1 - 0.1 / cos(30).
  ASSERT_TRUE(scene.OfferModel(ModelWithWall(true, M_PI / 6)).accepted);
  const auto hit = FirstWorldObjectHit(scene, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d::UnitX(), 10);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 3.1 - 0.1 / std::cos(M_PI / 6), 1e-9);
}

TEST(LineOfSightTest, TheCameraComesInFrontOfTheWallAndSeesTheRobot) {
  Scene scene;
  ASSERT_TRUE(scene.OfferModel(ModelWithWall(true)).accepted);
  const Camera user = LevelCameraOnTheRobot();
  const Camera drawn = UnblockedCamera(user, scene);
  EXPECT_NEAR(drawn.distance, 3.0 - kWallClearance, 1e-12);
  EXPECT_LT(drawn.Eye().x(), 3.0);  // this side of the wall
  EXPECT_EQ(user.distance, 5);      // the user's camera is unchanged
  // Nothing in the way at the drawn distance: the robot is in view.
  EXPECT_FALSE(FirstWorldObjectHit(scene, drawn.target, drawn.EyeDirection(), drawn.distance));
  // Turned away from the wall, the camera keeps its distance.
  Camera behind = user;
  behind.yaw = M_PI;
  EXPECT_EQ(UnblockedCamera(behind, scene).distance, 5);
}

TEST(LineOfSightTest, MovingObjectsAndTheRobotItselfDoNotBlock) {
  Scene scene;
  ASSERT_TRUE(scene.OfferModel(ModelWithWall(false)).accepted);  // a loose slab, not a wall
  EXPECT_EQ(UnblockedCamera(LevelCameraOnTheRobot(), scene).distance, 5);
  // The robot's own Ball (2, 1, 0) is on the line but is the robot's.
  Scene robot_only;
  ASSERT_TRUE(robot_only.OfferModel(TwoBodyModel(7)).accepted);
  EXPECT_EQ(UnblockedCamera(LevelCameraOnTheRobot(), robot_only).distance, 5);
}

TEST(LineOfSightTest, NeverCloserThanTheMinimum) {
  Scene scene;
  model_t m = ModelWithWall(true);
  m.bodies.back().initial_position[0] = 0.3;  // near face at 0.2 m
  ASSERT_TRUE(scene.OfferModel(m).accepted);
  EXPECT_EQ(UnblockedCamera(LevelCameraOnTheRobot(), scene).distance, kMinClearDistance);
}

}  // namespace
}  // namespace simpartner::viewer
