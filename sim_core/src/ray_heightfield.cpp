#include "ray_heightfield.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace simpartner::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Moller-Trumbore: the ray's distance to triangle (a, b, c), or infinity.
double RayTriangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-15) return kInf;
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(p) / det;
  if (u < -1e-12 || u > 1 + 1e-12) return kInf;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < -1e-12 || u + v > 1 + 1e-12) return kInf;
  const double t = e2.dot(q) / det;
  return t >= 0 ? t : kInf;
}

struct Grid {
  const model::Heightfield& field;
  double cell_x, cell_z;
  Eigen::Vector3d Point(int c, int r) const {
    return {-field.width / 2 + c * cell_x,
            field.scale * field.samples[static_cast<size_t>(r) * field.columns + c] + field.offset,
            -field.depth / 2 + r * cell_z};
  }
  // The ray's distance to cell (c, r)'s two triangles, or infinity.
  double Cell(int c, int r, const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
    const Eigen::Vector3d a = Point(c, r), b = Point(c + 1, r), cc = Point(c, r + 1),
                          dd = Point(c + 1, r + 1);
    return std::min(RayTriangle(o, d, a, cc, b), RayTriangle(o, d, dd, b, cc));
  }
};

// The ray's entry and exit distances through the slab lo <= o + t d <= hi.
bool Slab(double o, double d, double lo, double hi, double* t0, double* t1) {
  if (std::abs(d) < 1e-15) return o >= lo && o <= hi;
  double a = (lo - o) / d, b = (hi - o) / d;
  if (a > b) std::swap(a, b);
  *t0 = std::max(*t0, a);
  *t1 = std::min(*t1, b);
  return *t0 <= *t1;
}

}  // namespace

double RayHeightfield(const model::Heightfield& field, const Eigen::Isometry3d& pose,
                      const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                      double range) {
  if (field.rows < 2 || field.columns < 2) return range;
  const Eigen::Vector3d o = pose.inverse() * origin;
  const Eigen::Vector3d d = pose.linear().transpose() * direction;
  const double half_w = field.width / 2, half_d = field.depth / 2;
  if (std::abs(o.x()) <= half_w && std::abs(o.z()) <= half_d &&
      o.y() < field.HeightAt(o.x(), o.z()) - 1e-9 && o.y() > field.HeightAt(o.x(), o.z()) - field.thickness)
    return 0.0;
  double t0 = 0.0, t1 = range;
  if (!Slab(o.x(), d.x(), -half_w, half_w, &t0, &t1) || !Slab(o.z(), d.z(), -half_d, half_d, &t0, &t1))
    return range;
  const Grid grid{field, field.width / (field.columns - 1), field.depth / (field.rows - 1)};
  // Walk the cells under the ray from t0 to t1 (Amanatides and Woo).
  const Eigen::Vector3d start = o + t0 * d;
  int c = std::clamp(static_cast<int>(std::floor((start.x() + half_w) / grid.cell_x)), 0, field.columns - 2);
  int r = std::clamp(static_cast<int>(std::floor((start.z() + half_d) / grid.cell_z)), 0, field.rows - 2);
  const int step_c = d.x() > 0 ? 1 : -1, step_r = d.z() > 0 ? 1 : -1;
  auto next = [&](double pos, double dir, int index, int step, double cell, double half) {
    if (std::abs(dir) < 1e-15) return kInf;
    const double edge = -half + (index + (step > 0 ? 1 : 0)) * cell;
    return (edge - pos) / dir;
  };
  double next_c = next(o.x(), d.x(), c, step_c, grid.cell_x, half_w);
  double next_r = next(o.z(), d.z(), r, step_r, grid.cell_z, half_d);
  const double delta_c = std::abs(d.x()) < 1e-15 ? kInf : grid.cell_x / std::abs(d.x());
  const double delta_r = std::abs(d.z()) < 1e-15 ? kInf : grid.cell_z / std::abs(d.z());
  for (;;) {
    const double hit = grid.Cell(c, r, o, d);
    if (hit <= range) return hit;
    const double leave = std::min(next_c, next_r);
    if (leave > t1) return range;
    if (next_c < next_r) {
      c += step_c;
      next_c += delta_c;
    } else {
      r += step_r;
      next_r += delta_r;
    }
    if (c < 0 || c > field.columns - 2 || r < 0 || r > field.rows - 2) return range;
  }
}

}  // namespace simpartner::sim
