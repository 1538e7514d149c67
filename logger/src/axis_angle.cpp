#include "simpartner/logger/axis_angle.h"

#include <algorithm>
#include <cmath>

namespace simpartner::logger {

AxisAngle AxisAngleFromRotation(const Matrix3& r) {
  const double cos_angle =
      std::clamp((r[0][0] + r[1][1] + r[2][2] - 1.0) / 2.0, -1.0, 1.0);
  // Skew part: R - R^T = 2 sin(angle) [n]x.
  const std::array<double, 3> skew = {r[2][1] - r[1][2], r[0][2] - r[2][0],
                                      r[1][0] - r[0][1]};
  const double two_sin = std::sqrt(skew[0] * skew[0] + skew[1] * skew[1] + skew[2] * skew[2]);
  const double angle = std::atan2(two_sin / 2.0, cos_angle);

  if (two_sin == 0.0 && cos_angle > 0.0) return AxisAngle{{1.0, 0.0, 0.0}, 0.0};

  if (cos_angle >= 0.0) {
    // Up to pi/2 the skew part gives the axis directly. Its rounding error
    // is ~1e-16 / angle; near 0 that makes the axis loose, but any axis then
    // reproduces the rotation to rounding.
    return AxisAngle{{skew[0] / two_sin, skew[1] / two_sin, skew[2] / two_sin}, angle};
  }

  // Above pi/2: n n^T = (S - cos(a) I) / (1 - cos(a)), S the symmetric part.
  // The largest diagonal entry gives the best-conditioned component.
  int k = 0;
  if (r[1][1] > r[k][k]) k = 1;
  if (r[2][2] > r[k][k]) k = 2;
  const double one_minus_cos = 1.0 - cos_angle;  // in [1, 2]
  std::array<double, 3> axis{};
  axis[k] = std::sqrt(std::max(0.0, (r[k][k] - cos_angle) / one_minus_cos));
  for (int j = 0; j < 3; ++j) {
    if (j == k) continue;
    axis[j] = (r[k][j] + r[j][k]) / (2.0 * one_minus_cos * axis[k]);
  }
  // At exactly pi, n and -n are the same rotation: keep axis[k] positive.
  // Below pi the skew part fixes the direction.
  if (skew[k] < 0.0) {
    for (double& a : axis) a = -a;
  }
  const double norm = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (double& a : axis) a /= norm;
  return AxisAngle{axis, angle};
}

Matrix3 RotationFromQuaternion(const double q[4]) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  Matrix3 r;
  r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)};
  r[1] = {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)};
  r[2] = {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
  return r;
}

AxisAngle AxisAngleFromQuaternion(const double q[4]) {
  return AxisAngleFromRotation(RotationFromQuaternion(q));
}

}  // namespace simpartner::logger
