#include "simpartner/line_entry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace simpartner {
namespace {

// Below this a direction's component is taken as parallel to the slab.
constexpr double kParallel = 1e-12;

}  // namespace

std::optional<double> LineSpan::RayHit() const {
  if (leave < 0.0) return std::nullopt;
  return std::max(0.0, enter);
}

std::optional<LineSpan> LineThroughBox(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                       const Eigen::Vector3d& half) {
  LineSpan span{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < kParallel) {
      if (std::abs(p[k]) > half[k]) return std::nullopt;
      continue;
    }
    const double t1 = (-half[k] - p[k]) / d[k], t2 = (half[k] - p[k]) / d[k];
    span.enter = std::max(span.enter, std::min(t1, t2));
    span.leave = std::min(span.leave, std::max(t1, t2));
  }
  if (span.enter > span.leave) return std::nullopt;
  return span;
}

std::optional<LineSpan> LineThroughSphere(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                          const Eigen::Vector3d& c, double r) {
  const Eigen::Vector3d m = p - c;
  const double b = m.dot(d), disc = b * b - (m.squaredNorm() - r * r);
  if (disc < 0.0) return std::nullopt;
  const double root = std::sqrt(disc);
  return LineSpan{-b - root, -b + root};
}

}  // namespace simpartner
