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

void SoilRuts::Stamp(const std::vector<WheelSoilReadout>& wheels) {
  for (const WheelSoilReadout& wheel : wheels) {
    if (!(wheel.sinkage > 0.0)) continue;
    if (!has_surface_) {
      has_surface_ = true;
      origin_ = wheel.surface_origin;
      up_ = wheel.up;
      u_axis_ = wheel.surface_u_axis;
      w_axis_ = up_.cross(u_axis_);
    } else if ((wheel.up - up_).norm() > 1e-9 ||
               std::abs((wheel.surface_origin - origin_).dot(up_)) > 1e-9) {
      continue;  // another soil ground
    }
    const Eigen::Vector3d across = wheel.axle - wheel.axle.dot(up_) * up_;
    if (across.norm() < 1e-6) continue;  // a wheel lying flat presses no tread
    const Eigen::Vector3d on_surface = wheel.lowest_point + wheel.sinkage * up_;
    // Points at most half a cell apart across the tread.
    const double width = wheel.width;
    const int points = static_cast<int>(std::ceil(width / (0.5 * kCellSize))) + 1;
    for (int k = 0; k < points; ++k) {
      const double t = width * (static_cast<double>(k) / (points - 1) - 0.5);
      Press(on_surface + t * across.normalized(), static_cast<float>(wheel.sinkage));
    }
  }
}

void SoilRuts::Press(const Eigen::Vector3d& point, float depth) {
  const Eigen::Vector3d d = point - origin_;
  const double a = std::floor(d.dot(u_axis_) / kCellSize), b = std::floor(d.dot(w_axis_) / kCellSize);
  if (!(std::abs(a) < 2e9 && std::abs(b) < 2e9)) return;
  const uint64_t key = Key(static_cast<int32_t>(a), static_cast<int32_t>(b));
  auto it = cells_.find(key);
  if (it == cells_.end()) {
    if (full()) return;
    it = cells_.emplace(key, Cell{}).first;
  }
  Cell& cell = it->second;
  if (depth <= cell.depth) return;
  cell.depth = depth;
  if (!cell.queued && cell.depth >= cell.sent + kDepthResolution) {
    cell.queued = true;
    queued_.push_back(key);
  }
}

void SoilRuts::Clear() {
  has_surface_ = false;
  cells_.clear();
  queued_.clear();
}

soil_ruts_t SoilRuts::Header(bool snapshot) const {
  soil_ruts_t m{};
  m.snapshot = snapshot;
  m.part = 0;
  m.parts = 1;
  Eigen::Map<Eigen::Vector3d>(m.origin) = origin_;
  Eigen::Map<Eigen::Vector3d>(m.up) = up_;
  Eigen::Map<Eigen::Vector3d>(m.u_axis) = u_axis_;
  m.cell_size = kCellSize;
  m.num_cells = 0;
  return m;
}

soil_ruts_t SoilRuts::TakeChanges() {
  soil_ruts_t m = Header(false);
  const size_t n = std::min(queued_.size(), static_cast<size_t>(kCellsPerMessage));
  for (size_t i = queued_.size() - n; i < queued_.size(); ++i) {
    Cell& cell = cells_.at(queued_[i]);
    cell.queued = false;
    cell.sent = cell.depth;
    Append(&m, queued_[i], cell.depth);
  }
  queued_.resize(queued_.size() - n);
  return m;
}

std::vector<soil_ruts_t> SoilRuts::Snapshot() const {
  std::vector<soil_ruts_t> parts(1, Header(true));
  for (const auto& [key, cell] : cells_) {
    if (parts.back().num_cells == kCellsPerMessage) parts.push_back(Header(true));
    Append(&parts.back(), key, cell.depth);
  }
  for (size_t i = 0; i < parts.size(); ++i) {
    parts[i].part = static_cast<int32_t>(i);
    parts[i].parts = static_cast<int32_t>(parts.size());
  }
  return parts;
}

}  // namespace simpartner::sim
