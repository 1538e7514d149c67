#include "simpartner/rotation_between.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace simpartner {
namespace {

// The rotation takes `from` onto `to`, is proper, and turns about their
// common normal by the angle between them (the shortest rotation).
void ExpectShortestTurn(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Quaterniond q = RotationBetween(from, to);
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  const Eigen::Vector3d turned = q * from.normalized();
  EXPECT_NEAR((turned - to.normalized()).norm(), 0.0, 1e-12) << from.transpose() << " to " << to.transpose();
  const Eigen::AngleAxisd turn(q);
  EXPECT_NEAR(turn.angle(), std::acos(std::clamp(from.normalized().dot(to.normalized()), -1.0, 1.0)), 1e-9);
  EXPECT_NEAR(turn.axis().dot(from.normalized()), 0.0, 1e-9);
}

TEST(RotationBetween, TurnsTheShortestWayBetweenDirections) {
  ExpectShortestTurn(Eigen::Vector3d::UnitY(), Eigen::Vector3d(-std::sin(0.2), std::cos(0.2), 0));
  ExpectShortestTurn(Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.3, 0.9, -0.2));
  ExpectShortestTurn(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-3, 0.5, 2));
  ExpectShortestTurn(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ() * 5.0);  // lengths do not matter
}

TEST(RotationBetween, SameDirectionIsNoTurn) {
  const Eigen::Quaterniond q = RotationBetween(Eigen::Vector3d::UnitY(), Eigen::Vector3d(0, 2, 0));
  EXPECT_DOUBLE_EQ(q.w(), 1.0);
  EXPECT_DOUBLE_EQ(q.vec().norm(), 0.0);
}

// Gravity along +y (a world upside down): a half turn about a normal of y.
TEST(RotationBetween, OppositeDirectionsAreAHalfTurnAboutANormal) {
  const Eigen::Vector3d froms[] = {Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.2, -0.5, 0.8)};
  for (const Eigen::Vector3d& from : froms) {
    // -from normalised is opposite only to rounding: 1 + c is about 1e-16,
    // whose square root (the half angle's cosine) is about 1e-8.
    const Eigen::Quaterniond q = RotationBetween(from, -from);
    EXPECT_NEAR((q * from.normalized() + from.normalized()).norm(), 0.0, 1e-7);
    EXPECT_NEAR(std::abs(q.w()), 0.0, 1e-7);
    EXPECT_NEAR(q.vec().dot(from.normalized()), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace simpartner
