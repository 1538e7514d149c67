#pragma once
// The shortest rotation taking one direction to another, as the sim turns
// a heightfield from y to the world's up and the viewer draws it.
//
// Eigen's Quaternion::FromTwoVectors does the same, but its antiparallel
// case instantiates JacobiSVD, which costs a minute of compile time per
// file in a sanitized build; this is the same formula with a closed-form
// axis for that case.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace simpartner {

// The rotation q with q * from parallel to to, about from x to. Neither may
// be zero. When they are opposite, the half turn is about an axis normal to
// `from` (which one is not defined by the directions alone).
Eigen::Quaterniond RotationBetween(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

}  // namespace simpartner
