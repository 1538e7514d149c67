#include "simpartner/rotation_between.h"

#include <algorithm>
#include <cmath>

namespace simpartner {
namespace {

// A unit vector normal to unit `v`: across the axis v is least along.
Eigen::Vector3d AnyNormal(const Eigen::Vector3d& v) {
  Eigen::Index least = 0;
  v.cwiseAbs().minCoeff(&least);
  return v.cross(Eigen::Vector3d::Unit(least)).normalized();
}

}  // namespace

Eigen::Quaterniond RotationBetween(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d a = from.normalized();
  const Eigen::Vector3d b = to.normalized();
  const double c = a.dot(b);
  Eigen::Quaterniond q;
  // Near opposite the cross product has no direction left: a half turn.
  if (c < -1.0 + 1e-12) {
    const double w2 = (1.0 + std::max(c, -1.0)) * 0.5;
    q.w() = std::sqrt(w2);
    q.vec() = AnyNormal(a) * std::sqrt(1.0 - w2);
    return q;
  }
  // Half the angle: |a x b| = sin t, and s = 2 cos(t / 2).
  const double s = std::sqrt((1.0 + c) * 2.0);
  q.vec() = a.cross(b) / s;
  q.w() = s * 0.5;
  return q;
}

}  // namespace simpartner
