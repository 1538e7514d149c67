// Orientation as the original stored it in Pose: a unit axis and an angle in
// [0, pi] (SPEC 6). Pure functions, no state.
#pragma once

#include <array>

namespace simpartner::logger {

// Row-major rotation matrix: r[i][j] is R(i+1, j+1) in SPEC 6's notation.
using Matrix3 = std::array<std::array<double, 3>, 3>;

struct AxisAngle {
  std::array<double, 3> axis;  // unit vector, world frame
  double angle;                // [rad], 0 <= angle <= pi
};

// SPEC 6: angle = acos((R11 + R22 + R33 - 1) / 2); the axis from the skew
// part of R; at angle 0 the axis is (1, 0, 0); at angle pi the axis comes
// from the diagonal with signs from the off-diagonal terms (the component
// with the largest diagonal entry is positive).
//
// The angle is computed as atan2(|skew| / 2, (trace - 1) / 2): the same
// value as the acos for a rotation matrix, but without acos's loss of half
// the digits near 0 and pi. Above pi/2 the axis comes from the symmetric
// part (R + R^T)/2 = cos(a) I + (1 - cos(a)) n n^T, which stays accurate up
// to pi where the skew part vanishes; the skew part then only gives the sign.
AxisAngle AxisAngleFromRotation(const Matrix3& r);

// Rotation matrix of the quaternion (w, x, y, z), normalised first (any
// non-zero length; q and -q give the same matrix).
Matrix3 RotationFromQuaternion(const double q[4]);

// AxisAngleFromRotation(RotationFromQuaternion(q)).
AxisAngle AxisAngleFromQuaternion(const double q[4]);

}  // namespace simpartner::logger
