// Circle and line fits, and the ideal slipping vehicle the circle runs are
// compared with.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

#include "simpartner/validate/analysis.h"

namespace simpartner::validate {
namespace {

std::vector<Eigen::Vector2d> Arc(const Eigen::Vector2d& centre, double radius, double from,
                                 double to, int n) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < n; ++i) {
    const double a = from + (to - from) * i / (n - 1);
    points.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return points;
}

TEST(ValidateFitCircle, RecoversAFullCircle) {
  const CircleFit fit = FitCircle(Arc({3.0, -4.0}, 5.98, 0.0, 2.0 * M_PI, 500));
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.radius, 5.98, 1e-9);
  EXPECT_NEAR(fit.centre.x(), 3.0, 1e-9);
  EXPECT_NEAR(fit.centre.y(), -4.0, 1e-9);
  EXPECT_LT(fit.worst_deviation, 1e-9);
}

TEST(ValidateFitCircle, RecoversAQuarterArc) {
  // Kasa's algebraic fit alone is biased on short arcs with noise; the
  // geometric refinement must land on the circle.
  std::vector<Eigen::Vector2d> points = Arc({0.0, 0.0}, 4.01, 0.3, 0.3 + M_PI / 2, 200);
  for (size_t i = 0; i < points.size(); ++i)
    points[i] *= 1.0 + 1e-4 * ((i % 2) ? 1.0 : -1.0);  // +-0.4 mm
  const CircleFit fit = FitCircle(points);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.radius, 4.01, 1e-4);
  EXPECT_NEAR(fit.worst_deviation, 4.01e-4, 2e-5);
}

TEST(ValidateFitCircle, ReportsHowFarAPathLeavesItsCircle) {
  std::vector<Eigen::Vector2d> points = Arc({0.0, 0.0}, 6.0, 0.0, 2.0 * M_PI, 720);
  points[100] *= 1.0 + 0.01 / 6.0;  // one point 1 cm outside
  const CircleFit fit = FitCircle(points);
  EXPECT_NEAR(fit.worst_deviation, 0.01, 5e-4);
}

TEST(ValidateFitCircle, RefusesTooFewOrCollinearPoints) {
  EXPECT_FALSE(FitCircle({{0, 0}, {1, 1}}).ok);
  EXPECT_FALSE(FitCircle({{0, 0}, {1, 1}, {2, 2}, {3, 3}}).ok);
}

TEST(ValidateFitLine, SlopeAndIntercept) {
  const Eigen::Vector2d line = FitLine({0, 1, 2, 3}, {1, 3, 5, 7});
  EXPECT_NEAR(line.x(), 1.0, 1e-12);
  EXPECT_NEAR(line.y(), 2.0, 1e-12);
}

// Reference values solved independently (a separate Python script with the
// same equations: Coulomb force mu N against each wheel's slip, force and
// moment balance with the centripetal force of 136 kg at the joint, loads
// 316 N front and 351 N rear per wheel).
TEST(ValidateSkidSteerRadius, MatchedSpeedsGiveTheKinematicRadius) {
  SkidSteerVehicle v;
  v.front_load = 316.0;
  v.rear_load = 351.0;
  v.alpha = 0.2;
  v.v_left = 1.0;
  v.v_right = (5.98 + 0.3) / (5.98 - 0.3);
  EXPECT_NEAR(SkidSteerRadius(v), 0.6 / std::tan(0.1), 1e-3);
}

TEST(ValidateSkidSteerRadius, SlippingWheelsTurnWiderThanTheSteering) {
  SkidSteerVehicle v;
  v.front_load = 316.0;
  v.rear_load = 351.0;
  v.alpha = 0.2972;
  EXPECT_NEAR(SkidSteerRadius(v), 4.9143, 1e-3);  // equal speeds
  v.mu = 0.5;
  EXPECT_NEAR(SkidSteerRadius(v), 4.9230, 1e-3);
  v.mu = 1.0;
  v.alpha = 0.2;
  v.v_right = 1.1;
  EXPECT_NEAR(SkidSteerRadius(v), 6.0389, 1e-3);
}

// A wheel touching at its two rim edges, each with half its load: as the
// edges close in, the point wheel's answer; 0.14 m apart (gen1's wheels),
// the edges scrub, which the point misses, and the answer moves.
TEST(ValidateSkidSteerRadius, TwoRimEdgesCloseTogetherAreThePointWheel) {
  SkidSteerVehicle v;
  v.front_load = 316.0;
  v.rear_load = 351.0;
  v.alpha = 0.2972;
  const double point = SkidSteerRadius(v);
  v.contact_half_width = 1e-5;
  EXPECT_NEAR(SkidSteerRadius(v), point, 1e-4);
  v.contact_half_width = 0.07;
  EXPECT_GT(std::abs(SkidSteerRadius(v) - point), 0.001);
}

// Per-wheel loads: the same loads given per wheel give the per-axle answer
// (front left, front right, rear left, rear right), and moving load to the
// outer (right) wheels of a left turn, whose slip pushes outwards, turns
// the vehicle tighter: the inner wheels' inward slip then weighs more.
TEST(ValidateSkidSteerRadius, PerWheelLoadsReplaceThePerAxleOnes) {
  SkidSteerVehicle v;
  v.front_load = 316.0;
  v.rear_load = 351.0;
  v.alpha = 0.2972;
  const double per_axle = SkidSteerRadius(v);
  const double same[4] = {316.0, 316.0, 351.0, 351.0};
  std::copy(same, same + 4, v.wheel_loads);
  EXPECT_NEAR(SkidSteerRadius(v), per_axle, 1e-9);
  const double shifted[4] = {266.0, 366.0, 301.0, 401.0};  // 50 N outwards on each axle
  std::copy(shifted, shifted + 4, v.wheel_loads);
  EXPECT_LT(SkidSteerRadius(v), per_axle);
}

// The steady state with the inner wheels rolling, at speeds matched to the
// steering: every wheel rolls, nothing slides, and the held inner wheels
// give the whole centripetal force m w^2 rho of the mass at the joint,
// rho = a / sin(alpha/2) from the turn's centre, w = v_inner / (R - t),
// R = a cot(alpha/2). With equal loads the two share it equally (the
// vehicle is symmetric about the line from the joint to the centre).
TEST(ValidateSkidSteerRolling, MatchedSpeedsNeedOnlyTheCentripetalForce) {
  SkidSteerVehicle v;
  v.front_load = v.rear_load = 330.0;
  v.alpha = 0.2;
  const double r = 0.6 / std::tan(0.1);
  v.v_left = 1.0;
  v.v_right = (r + 0.3) / (r - 0.3);
  const SkidSteerRolling rolling = SkidSteerRollingInnerWheels(v);
  EXPECT_NEAR(rolling.radius, r, 1e-9);
  EXPECT_EQ(rolling.edge, 0);
  const double w = 1.0 / (r - 0.3), rho = 0.6 / std::sin(0.1);
  EXPECT_NEAR(rolling.friction_needed, v.mass * w * w * rho / 2.0 / 330.0, 1e-6);
}

// gen1's circle at 1.00 / 1.10 m/s on rim edges 0.14 m apart: with half of
// each wheel's load on each edge, the held inner edges would need more than
// mu N, and the all-sliding steady state turns wider than the steering.
// With 60 % of the inner wheels' load on their edges nearer the middle
// (the sim puts 53 and 60 % there) they need less than mu N, and the
// sliding solve, started as always from the steering's radius, finds that
// steady state: the steering's circle.
TEST(ValidateSkidSteerRolling, InnerWheelsRollWhenTheirHeldEdgesCarryEnough) {
  SkidSteerVehicle v;
  v.front_load = v.rear_load = 333.5;
  v.alpha = 0.2;
  v.v_right = 1.1;
  v.contact_half_width = 0.07;
  const double steering = 0.6 / std::tan(0.1);
  const SkidSteerRolling even = SkidSteerRollingInnerWheels(v);
  EXPECT_GT(even.friction_needed, 1.0);
  EXPECT_GT(SkidSteerRadius(v), steering + 0.02);
  v.middle_edge_share[0] = v.middle_edge_share[2] = 0.6;  // front left, rear left
  const SkidSteerRolling uneven = SkidSteerRollingInnerWheels(v);
  EXPECT_LT(uneven.friction_needed, 1.0);
  EXPECT_EQ(uneven.edge, -1);
  EXPECT_NEAR(uneven.radius, steering, 1e-9);
  EXPECT_NEAR(SkidSteerRadius(v), steering, 1e-3);
}

}  // namespace
}  // namespace simpartner::validate
