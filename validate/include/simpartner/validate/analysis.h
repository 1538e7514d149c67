// Small numerical tools the experiments share: fitting a circle to a
// trajectory, linear fits, averages.
#pragma once

#include <Eigen/Core>
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
};
double SkidSteerRadius(const SkidSteerVehicle& vehicle);

}  // namespace simpartner::validate
