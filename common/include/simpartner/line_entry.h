#pragma once
// Where a line p + t d (d a unit vector) passes through a box or a
// sphere: the t at which it enters and leaves, either of which may be
// negative (behind p). The sim finds a body's underside above the soil
// with it and the viewer what hides its camera; each takes the part it
// needs (a line's entry, or a ray's first hit at t >= 0).

#include <optional>

#include <Eigen/Core>

namespace simpartner {

struct LineSpan {
  double enter = 0.0, leave = 0.0;
  // The first point at t >= 0 of the ray from p: 0 when p is inside;
  // nullopt when the span is all behind p.
  std::optional<double> RayHit() const;
};

// Through the axis-aligned box of half extents `half` about the origin
// (the slab method); nullopt when the line misses it.
std::optional<LineSpan> LineThroughBox(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                       const Eigen::Vector3d& half);

// Through the sphere of radius r about c; nullopt when the line misses it.
std::optional<LineSpan> LineThroughSphere(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                          const Eigen::Vector3d& c, double r);

}  // namespace simpartner
