// The ruts wheels pressed into soft soil, as the viewer learns them from
// SIM_SOIL_RUTS (soil_ruts_t): square cells of the soil's surface and how
// deep each was pressed, on the surface plane or on the heightfield (its
// base plane's grid). No GL here: the renderer draws RutMesh.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "simpartner/model_t.hpp"
#include "simpartner/soil_ruts_t.hpp"
#include "simpartner/viewer/mesh.h"

namespace simpartner::viewer {

// A message that passed CheckSoilRuts (message_checks.h): its ground is one of `model`'s (whose up is `up`), the
// grid on it: the plane's normal and a point of it, or the heightfield's
// frame (HeightfieldPose). Returns the first problem.
std::optional<std::string> CheckRutsGround(const soil_ruts_t& message, const model_t& model,
                                           const Eigen::Vector3d& up);

class RutMap {
 public:
  // Cells kept at most (a 100 m track of four 0.3 m wide wheels in 2 cm
  // cells takes 60,000); beyond it new cells are left out.
  static constexpr size_t kMaxCells = 1000000;

  // Takes a checked message (CheckSoilRuts) of this map's ground: a
  // snapshot's first part, or a message on another surface or cell size,
  // replaces every cell; the rest deepen theirs. Returns false when cells
  // were left out (full).
  bool Take(const soil_ruts_t& message);
  void Clear();

  size_t cells() const { return depth_.size(); }
  // Bumped on every change, so a cached mesh knows to rebuild.
  int64_t generation() const { return generation_; }
  // The deepest cell [m], 0 when none.
  double deepest() const;
  // The world position of cell (u, w)'s centre on the grid's plane (on a
  // heightfield: its base plane).
  Eigen::Vector3d CellCentre(int32_t u, int32_t w) const;
  const std::map<std::pair<int32_t, int32_t>, float>& depths() const { return depth_; }
  const Eigen::Vector3d& up() const { return up_; }
  const Eigen::Vector3d& u_axis() const { return u_axis_; }
  const Eigen::Vector3d& origin() const { return origin_; }
  double cell_size() const { return cell_size_; }

 private:
  bool SameSurface(const soil_ruts_t& message) const;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero(), up_ = Eigen::Vector3d::UnitY(),
                  u_axis_ = Eigen::Vector3d::UnitX();
  double cell_size_ = 0.0;
  std::map<std::pair<int32_t, int32_t>, float> depth_;
  int64_t generation_ = 0;
};

// Each cell as a square lowered into the ground (indexed: 4 vertices, 2
// triangles facing up), each corner by the mean depth of the four cells
// around it (0 where untouched): neighbours meet without gaps and a rut's
// edges slope up to the surface. On a heightfield (`field`, the ruts'
// grid on its base plane: CheckRutsGround) each corner is lowered from the
// field's surface above it as drawn. Coloured `color` darkened by a
// third, and by half at 5 cm deep and deeper.
Mesh RutMesh(const RutMap& ruts, const Eigen::Vector3f& color,
             const heightfield_t* field = nullptr);
// The ruts' opening: the same squares on the untouched ground as drawn
// (white). The renderer draws a rut's floor only where its opening is
// seen, so terrain in front hides the rut.
Mesh RutOpeningMesh(const RutMap& ruts, const heightfield_t* field = nullptr);

}  // namespace simpartner::viewer
