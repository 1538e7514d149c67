#include "simpartner/viewer/soil_ruts.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "simpartner/text.h"

namespace simpartner::viewer {
namespace {

Eigen::Vector3d Vec(const double (&v)[3]) { return Eigen::Vector3d(v[0], v[1], v[2]); }

std::string Triple(const double (&v)[3]) {
  return "(" + FormatNumber(v[0]) + ", " + FormatNumber(v[1]) + ", " + FormatNumber(v[2]) + ")";
}

}  // namespace

std::optional<std::string> CheckRutsGround(const soil_ruts_t& m, const model_t& model,
                                           const Eigen::Vector3d& up) {
  // The sim computes the frame from the same numbers: equal but rounding.
  constexpr double kSame = 1e-6;
  if (m.ground == soil_ruts_t::GROUND_PLANE) {
    if (!model.has_plane) return std::string("ground = 0 but the model has no surface plane");
    const Eigen::Vector3d n = Eigen::Vector3d(model.plane[0], model.plane[1], model.plane[2]);
    if ((Vec(m.up) - n.normalized()).norm() > kSame ||
        std::abs(Vec(m.origin).dot(n) - model.plane[3]) > kSame * n.norm())
      return "up = " + Triple(m.up) + ", origin = " + Triple(m.origin) +
             " are not the model's surface plane";
    return std::nullopt;
  }
  if (!model.heightfield.present) return std::string("ground = 1 but the model has no heightfield");
  const Eigen::Isometry3d pose = HeightfieldPose(model.heightfield, up);
  if ((Vec(m.origin) - pose.translation()).norm() > kSame || (Vec(m.up) - pose.linear().col(1)).norm() > kSame ||
      (Vec(m.u_axis) - pose.linear().col(0)).norm() > kSame)
    return "origin = " + Triple(m.origin) + ", up = " + Triple(m.up) + ", u_axis = " +
           Triple(m.u_axis) + " are not the heightfield's frame";
  return std::nullopt;
}

bool RutMap::SameSurface(const soil_ruts_t& m) const {
  return m.cell_size == cell_size_ && Vec(m.origin) == origin_ && Vec(m.up) == up_ &&
         Vec(m.u_axis) == u_axis_;
}

bool RutMap::Take(const soil_ruts_t& m) {
  if ((m.snapshot && m.part == 0) || !SameSurface(m)) {
    depth_.clear();
    origin_ = Vec(m.origin);
    up_ = Vec(m.up);
    u_axis_ = Vec(m.u_axis);
    cell_size_ = m.cell_size;
  }
  ++generation_;
  bool all = true;
  for (size_t i = 0; i < m.depth.size(); ++i) {
    const std::pair<int32_t, int32_t> cell{m.u[i], m.w[i]};
    auto it = depth_.find(cell);
    if (it == depth_.end()) {
      if (depth_.size() >= kMaxCells) {
        all = false;
        continue;
      }
      it = depth_.emplace(cell, 0.0f).first;
    }
    // The ruts only deepen: a change that arrives late does not undo one.
    it->second = std::max(it->second, m.depth[i]);
  }
  return all;
}

void RutMap::Clear() {
  depth_.clear();
  cell_size_ = 0.0;
  ++generation_;
}

double RutMap::deepest() const {
  float deepest = 0.0f;
  for (const auto& [cell, depth] : depth_) deepest = std::max(deepest, depth);
  return deepest;
}

Eigen::Vector3d RutMap::CellCentre(int32_t u, int32_t w) const {
  const Eigen::Vector3d w_axis = up_.cross(u_axis_);
  return origin_ + cell_size_ * ((u + 0.5) * u_axis_ + (w + 0.5) * w_axis);
}

namespace {

// The depth at the corner of four cells (corner (u, w) is the one cell
// (u, w) has at its lowest u and w): their mean, untouched cells counting
// 0, so that neighbours meet without gaps and a rut's edges slope up to
// the surface.
double CornerDepth(const RutMap& ruts, int64_t u, int64_t w) {
  double sum = 0.0;
  for (int64_t du : {-1, 0})
    for (int64_t dw : {-1, 0}) {
      const int64_t cu = u + du, cw = w + dw;
      if (cu < INT32_MIN || cu > INT32_MAX || cw < INT32_MIN || cw > INT32_MAX) continue;
      const auto it = ruts.depths().find({static_cast<int32_t>(cu), static_cast<int32_t>(cw)});
      if (it != ruts.depths().end()) sum += it->second;
    }
  return 0.25 * sum;
}

// The corners of the ruts' cells: on the untouched ground as drawn (the
// plane, or the field's surface above the grid's base plane; the field's
// frame: x along u_axis, y up), or lowered into it by CornerDepth.
class CellCorners {
 public:
  CellCorners(const RutMap& ruts, const heightfield_t* field) : ruts_(ruts), field_(field) {}

  std::array<Eigen::Vector3d, 4> Of(std::pair<int32_t, int32_t> cell, bool lowered) const {
    const int64_t u = cell.first, w = cell.second;
    const Eigen::Vector3d c = ruts_.CellCentre(cell.first, cell.second);
    std::array<Eigen::Vector3d, 4> corners = {Surface(c - a_ - b_), Surface(c + a_ - b_),
                                              Surface(c + a_ + b_), Surface(c - a_ + b_)};
    if (lowered) {
      corners[0] -= CornerDepth(ruts_, u, w) * up_;
      corners[1] -= CornerDepth(ruts_, u + 1, w) * up_;
      corners[2] -= CornerDepth(ruts_, u + 1, w + 1) * up_;
      corners[3] -= CornerDepth(ruts_, u, w + 1) * up_;
    }
    return corners;
  }

 private:
  Eigen::Vector3d Surface(const Eigen::Vector3d& p) const {
    if (field_ == nullptr) return p;
    const Eigen::Vector3d d = p - ruts_.origin();
    return p + HeightfieldSurface(*field_, d.dot(ruts_.u_axis()), d.dot(field_z_)) * up_;
  }

  const RutMap& ruts_;
  const heightfield_t* field_;
  const Eigen::Vector3d up_ = ruts_.up(), field_z_ = ruts_.u_axis().cross(up_);
  // Half a cell along each axis of the grid.
  const Eigen::Vector3d a_ = 0.5 * ruts_.cell_size() * ruts_.u_axis(),
                        b_ = 0.5 * ruts_.cell_size() * up_.cross(ruts_.u_axis());
};

// One square per cell, lowered or not (CellCorners): two triangles facing
// up with the cell's normal across its diagonals, coloured `color`,
// lowered ones darkened by a third and by half at 5 cm deep and deeper.
Mesh CellSquares(const RutMap& ruts, const heightfield_t* field, bool lowered,
                 const Eigen::Vector3f& color) {
  Mesh mesh;
  const CellCorners corners_of(ruts, field);
  mesh.positions.reserve(4 * ruts.cells());
  mesh.normals.reserve(4 * ruts.cells());
  mesh.colors.reserve(4 * ruts.cells());
  mesh.indices.reserve(6 * ruts.cells());
  for (const auto& [cell, depth] : ruts.depths()) {
    const std::array<Eigen::Vector3d, 4> corners = corners_of.Of(cell, lowered);
    const Eigen::Vector3f normal =
        (corners[2] - corners[0]).cross(corners[3] - corners[1]).normalized().cast<float>();
    const float shade =
        lowered ? 1.0f - std::min(0.5f, 0.33f + 0.17f * std::min(1.0f, depth / 0.05f)) : 1.0f;
    const auto first = static_cast<uint32_t>(mesh.positions.size());
    for (const Eigen::Vector3d& corner : corners) {
      mesh.positions.push_back(corner.cast<float>());
      mesh.normals.push_back(normal);
      mesh.colors.push_back(shade * color);
    }
    for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + k);
  }
  return mesh;
}

}  // namespace

Mesh RutMesh(const RutMap& ruts, const Eigen::Vector3f& color, const heightfield_t* field) {
  return CellSquares(ruts, field, true, color);
}

Mesh RutOpeningMesh(const RutMap& ruts, const heightfield_t* field) {
  return CellSquares(ruts, field, false, Eigen::Vector3f::Ones());
}

}  // namespace simpartner::viewer
