// Small numerical tools the experiments share: fitting a circle to a
// trajectory, linear fits, averages.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace simpartner::validate {

struct CircleFit {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  double worst_deviation = 0.0;  // largest | |p - centre| - radius | over the points
  double rms_deviation = 0.0;
  bool ok = false;               // false for fewer than 3 points or collinear points
};

// Geometric least-squares circle through 2-D points (Kasa's algebraic fit,
// refined by Gauss-Newton on the distances).
CircleFit FitCircle(const std::vector<Eigen::Vector2d>& points);

// Least-squares line y = a + b x; returns {a, b}.
Eigen::Vector2d FitLine(const std::vector<double>& x, const std::vector<double>& y);

double Mean(const std::vector<double>& values);

// Steady turn of an ideal articulated vehicle that slips: two rigid halves
// at a fixed steering angle alpha, each with an axle a ahead of / behind the
// joint carrying two point wheels half_track either side, the left wheels'
// rims at v_left, the right ones' at v_right [m/s]; every contact slides
// with isotropic Coulomb friction (force mu N against its slip velocity).
// Solves the force and moment balance (with the centripetal force of the
// whole mass at the joint) for the rotation centre; returns the radius of
// the rear axle midpoint's path, or NaN when it does not converge. With
// speeds matched to the steering it is the kinematic a cot(alpha/2).
struct SkidSteerVehicle {
  double alpha = 0.0;           // [rad], > 0 turns left
  double v_left = 1.0, v_right = 1.0;
  double axle = 0.6, half_track = 0.3;
  double mass = 136.0;          // [kg]
  double mu = 1.0;
  double front_load = 1.0, rear_load = 1.0;  // [N] per wheel
  // [N] front left, front right, rear left, rear right; when set (all > 0)
  // they replace front_load and rear_load (a turn moves load outwards).
  double wheel_loads[4] = {0.0, 0.0, 0.0, 0.0};
  // [m] A wheel touching along a line (a cylinder's two rim edges, each
  // carrying half its load) rather than at one point: the yaw rate makes
  // the two edges slide at different speeds, a scrub the point misses.
  double contact_half_width = 0.0;
  // With two edges: the share of each wheel's load (same order as
  // wheel_loads) on its edge nearer the vehicle's middle; 0 = half.
  double middle_edge_share[4] = {0.0, 0.0, 0.0, 0.0};
};
double SkidSteerRadius(const SkidSteerVehicle& vehicle);

// A second steady state of the same vehicle, when the inner (slower) wheels
// can roll: the whole vehicle turns about the point where its axle lines
// cross, each inner wheel holding one contact (an edge, or the point) at
// rest on the ground while the others slide with mu N against their slip.
// It is a Coulomb steady state when the two held contacts can balance the
// sliding ones and the centripetal force within mu N each:
// friction_needed, the smallest possible max |F| / (mu N) of the two, is
// at most 1. radius as SkidSteerRadius's (a cot(alpha/2), the steering's
// own circle); edge -1 inner rim edge, +1 outer, 0 a point wheel.
struct SkidSteerRolling {
  double radius = std::numeric_limits<double>::quiet_NaN();
  double friction_needed = std::numeric_limits<double>::infinity();
  int edge = 0;
};
SkidSteerRolling SkidSteerRollingInnerWheels(const SkidSteerVehicle& vehicle);

}  // namespace simpartner::validate
