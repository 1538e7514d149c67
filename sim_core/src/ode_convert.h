// Eigen <-> ODE vectors and rotations, for the ODE engine's files.
#pragma once

#include <ode/ode.h>

#include <Eigen/Core>

namespace simpartner::sim {

inline Eigen::Vector3d FromOde(const dReal* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

inline void ToOdeVector(const Eigen::Vector3d& v, dReal* out) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

// A rotation into ODE's 3 x 4 row-major dMatrix3.
inline void ToOde(const Eigen::Matrix3d& r, dMatrix3 out) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out[i * 4 + j] = r(i, j);
    out[i * 4 + 3] = 0.0;
  }
}

// ODE's 3 x 4 row-major dMatrix3 as a rotation.
inline Eigen::Matrix3d FromOdeRotation(const dReal* r) {
  Eigen::Matrix3d out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out(i, j) = r[i * 4 + j];
  return out;
}

}  // namespace simpartner::sim
