#include "simpartner/sim/soil_ruts.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace simpartner::sim {
namespace {

// Cell indices as one key, and back (two's complement, 32 bits each:
// shifting a negative signed value is undefined).
uint64_t Key(int32_t u, int32_t w) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(u)) << 32) | static_cast<uint32_t>(w);
}
int32_t KeyU(uint64_t key) { return static_cast<int32_t>(static_cast<uint32_t>(key >> 32)); }
int32_t KeyW(uint64_t key) { return static_cast<int32_t>(static_cast<uint32_t>(key)); }

void Append(soil_ruts_t* message, uint64_t key, float depth) {
  message->u.push_back(KeyU(key));
  message->w.push_back(KeyW(key));
  message->depth.push_back(depth);
  message->num_cells = static_cast<int32_t>(message->depth.size());
}

}  // namespace

SoilRuts::SoilRuts(const model::World& world) {
  if (world.heightfield && world.FindSoil(world.heightfield->material) != nullptr) {
    const Eigen::Isometry3d pose = world.HeightfieldPose();
    Grid& grid = grids_[soil_ruts_t::GROUND_HEIGHTFIELD];
    grid.has_frame = true;
    grid.origin = pose.translation();
    grid.up = pose.linear().col(1);
    grid.u_axis = pose.linear().col(0);
    grid.w_axis = grid.up.cross(grid.u_axis);
  }
}

SoilRuts::Grid* SoilRuts::GridOf(const WheelSoilReadout& wheel) {
  if (wheel.ground == SoilGround::kHeightfield) {
    Grid& field = grids_[soil_ruts_t::GROUND_HEIGHTFIELD];
    return field.has_frame ? &field : nullptr;
  }
  // A world has one plane: its frame as the engine reports it.
  Grid& grid = grids_[soil_ruts_t::GROUND_PLANE];
  if (!grid.has_frame) {
    grid.has_frame = true;
    grid.origin = wheel.surface_origin;
    grid.up = wheel.up;
    grid.u_axis = wheel.surface_u_axis;
    grid.w_axis = grid.up.cross(grid.u_axis);
  }
  return &grid;
}

void SoilRuts::Stamp(const std::vector<WheelSoilReadout>& wheels) {
  for (const WheelSoilReadout& wheel : wheels) {
    if (!(wheel.sinkage > 0.0)) continue;
    Grid* grid = GridOf(wheel);
    if (grid == nullptr) continue;
    const Eigen::Vector3d across = wheel.axle - wheel.axle.dot(wheel.up) * wheel.up;
    if (across.norm() < 1e-6) continue;  // a wheel lying flat presses no tread
    const Eigen::Vector3d on_surface = wheel.lowest_point + wheel.sinkage * wheel.up;
    // The sinkage is along the surface's normal under the wheel; the grid
    // keeps it along its own up (the same on a plane; on a slope of the
    // field the normal's offset of a plane, measured along up).
    const double depth = wheel.sinkage / std::max(0.1, wheel.up.dot(grid->up));
    // Points at most half a cell apart across the tread.
    const double width = wheel.width;
    const int points = static_cast<int>(std::ceil(width / (0.5 * kCellSize))) + 1;
    for (int k = 0; k < points; ++k) {
      const double t = width * (static_cast<double>(k) / (points - 1) - 0.5);
      Press(grid, on_surface + t * across.normalized(), static_cast<float>(depth));
    }
  }
}

void SoilRuts::Press(Grid* grid, const Eigen::Vector3d& point, float depth) {
  const Eigen::Vector3d d = point - grid->origin;
  const double a = std::floor(d.dot(grid->u_axis) / kCellSize),
               b = std::floor(d.dot(grid->w_axis) / kCellSize);
  if (!(std::abs(a) < 2e9 && std::abs(b) < 2e9)) return;
  const uint64_t key = Key(static_cast<int32_t>(a), static_cast<int32_t>(b));
  auto it = grid->cells.find(key);
  if (it == grid->cells.end()) {
    if (full()) return;
    it = grid->cells.emplace(key, Cell{}).first;
  }
  Cell& cell = it->second;
  if (depth <= cell.depth) return;
  cell.depth = depth;
  if (!cell.queued && cell.depth >= cell.sent + kDepthResolution) {
    cell.queued = true;
    grid->queued.push_back(key);
  }
}

void SoilRuts::Clear() {
  for (Grid& grid : grids_) {
    // The field's frame is the model's; the plane's, the first wheel's.
    if (grid.ground == soil_ruts_t::GROUND_PLANE) grid.has_frame = false;
    grid.cells.clear();
    grid.queued.clear();
  }
}

bool SoilRuts::has_changes() const {
  return !grids_[0].queued.empty() || !grids_[1].queued.empty();
}

size_t SoilRuts::cells() const { return grids_[0].cells.size() + grids_[1].cells.size(); }

soil_ruts_t SoilRuts::Header(const Grid& grid, bool snapshot) const {
  soil_ruts_t m{};
  m.snapshot = snapshot;
  m.part = 0;
  m.parts = 1;
  Eigen::Map<Eigen::Vector3d>(m.origin) = grid.origin;
  Eigen::Map<Eigen::Vector3d>(m.up) = grid.up;
  Eigen::Map<Eigen::Vector3d>(m.u_axis) = grid.u_axis;
  m.cell_size = kCellSize;
  m.num_cells = 0;
  m.ground = grid.ground;
  return m;
}

soil_ruts_t SoilRuts::TakeChanges() {
  // Each ground in turn, so that one never starves the other.
  if (grids_[next_grid_].queued.empty()) next_grid_ = 1 - next_grid_;
  Grid& grid = grids_[next_grid_];
  next_grid_ = 1 - next_grid_;
  soil_ruts_t m = Header(grid, false);
  const size_t n = std::min(grid.queued.size(), static_cast<size_t>(kCellsPerMessage));
  for (size_t i = grid.queued.size() - n; i < grid.queued.size(); ++i) {
    Cell& cell = grid.cells.at(grid.queued[i]);
    cell.queued = false;
    cell.sent = cell.depth;
    Append(&m, grid.queued[i], cell.depth);
  }
  grid.queued.resize(grid.queued.size() - n);
  return m;
}

std::vector<soil_ruts_t> SoilRuts::Snapshot() const {
  std::vector<soil_ruts_t> all;
  for (const Grid& grid : grids_) {
    if (grid.cells.empty()) continue;
    std::vector<soil_ruts_t> parts(1, Header(grid, true));
    for (const auto& [key, cell] : grid.cells) {
      if (parts.back().num_cells == kCellsPerMessage) parts.push_back(Header(grid, true));
      Append(&parts.back(), key, cell.depth);
    }
    for (size_t i = 0; i < parts.size(); ++i) {
      parts[i].part = static_cast<int32_t>(i);
      parts[i].parts = static_cast<int32_t>(parts.size());
    }
    all.insert(all.end(), parts.begin(), parts.end());
  }
  if (all.empty()) all.push_back(Header(grids_[soil_ruts_t::GROUND_PLANE], true));
  return all;
}

}  // namespace simpartner::sim
