// Lines through a box and a sphere, against spans worked out by hand.
#include "simpartner/line_entry.h"

#include <gtest/gtest.h>

namespace simpartner {
namespace {

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX();

TEST(LineEntry, ThroughABoxFromOutsideInsideAndBehind) {
  const Eigen::Vector3d half(1, 2, 3);
  // From x = -5 along +x: enters at x = -1 (t 4), leaves at x = 1 (t 6).
  const auto ahead = LineThroughBox(Eigen::Vector3d(-5, 0, 0), kX, half);
  ASSERT_TRUE(ahead);
  EXPECT_DOUBLE_EQ(ahead->enter, 4.0);
  EXPECT_DOUBLE_EQ(ahead->leave, 6.0);
  EXPECT_DOUBLE_EQ(*ahead->RayHit(), 4.0);
  // From inside: the line entered behind; the ray hits at once.
  const auto inside = LineThroughBox(Eigen::Vector3d(0.5, 0, 0), kX, half);
  ASSERT_TRUE(inside);
  EXPECT_DOUBLE_EQ(inside->enter, -1.5);
  EXPECT_DOUBLE_EQ(*inside->RayHit(), 0.0);
  // Past it: the line met it, the ray does not.
  const auto behind = LineThroughBox(Eigen::Vector3d(5, 0, 0), kX, half);
  ASSERT_TRUE(behind);
  EXPECT_FALSE(behind->RayHit());
  // Parallel to a face and beside the box: no span.
  EXPECT_FALSE(LineThroughBox(Eigen::Vector3d(-5, 2.5, 0), kX, half));
  // Down onto the top face, as the sim looks for a body's underside.
  const auto down = LineThroughBox(Eigen::Vector3d(0.3, 0.4, -10), Eigen::Vector3d::UnitZ(), half);
  ASSERT_TRUE(down);
  EXPECT_DOUBLE_EQ(down->enter, 7.0);
}

TEST(LineEntry, ThroughASphere) {
  const Eigen::Vector3d c(0, 1, 0);
  // Along y = 1.6 past a sphere of radius 1: the chord's half is 0.8.
  const auto chord = LineThroughSphere(Eigen::Vector3d(-3, 1.6, 0), kX, c, 1.0);
  ASSERT_TRUE(chord);
  EXPECT_NEAR(chord->enter, 2.2, 1e-12);
  EXPECT_NEAR(chord->leave, 3.8, 1e-12);
  EXPECT_FALSE(LineThroughSphere(Eigen::Vector3d(-3, 2.1, 0), kX, c, 1.0));
  // From the centre: the ray hits at once.
  EXPECT_DOUBLE_EQ(*LineThroughSphere(c, kX, c, 1.0)->RayHit(), 0.0);
  // Moving away from it: no hit ahead.
  EXPECT_FALSE(LineThroughSphere(Eigen::Vector3d(3, 1, 0), kX, c, 1.0)->RayHit());
}

}  // namespace
}  // namespace simpartner
