// The ruts wheels press into soft soil, as the viewer draws them (issue
// 28, docs/soil.md): on a grid of kCellSize cells of the soil's surface,
// the deepest sinkage a wheel's lowest rim point reached, stamped across
// its tread. Fed each step's wheel readouts; gives SIM_SOIL_RUTS
// messages: the cells deepened since the last one, or every cell.
// The soil's own memory (2 mm cells along each wheel's mid-plane) stays
// the engine's: this is its picture, coarse enough to draw and to send.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "simpartner/sim/engine.h"
#include "simpartner/soil_ruts_t.hpp"

namespace simpartner::sim {

class SoilRuts {
 public:
  static constexpr double kCellSize = 0.02;  // [m]
  // Cells in one message (soil_ruts_t's bound), and in the whole picture:
  // beyond it new cells are not recorded (a 100 m track of four 0.3 m
  // wide wheels takes 60,000).
  static constexpr int32_t kCellsPerMessage = 8192;
  static constexpr size_t kMaxCells = 1000000;
  // A cell is sent again once it is this much deeper than when last sent.
  static constexpr float kDepthResolution = 0.0005f;  // [m]

  // Stamps each wheel's tread into the grid. The grid lies on the first
  // soil surface met; wheels on another are left out (one soil ground is
  // all the worlds have).
  void Stamp(const std::vector<WheelSoilReadout>& wheels);
  void Clear();

  bool has_changes() const { return !queued_.empty(); }
  size_t cells() const { return cells_.size(); }
  bool full() const { return cells_.size() >= kMaxCells; }

  // The cells deepened since the last call (at most kCellsPerMessage; the
  // rest come with the next), as a message without utime, simulation id
  // and step.
  soil_ruts_t TakeChanges();
  // Every cell, in parts of at most kCellsPerMessage (one empty part when
  // there are none).
  std::vector<soil_ruts_t> Snapshot() const;

 private:
  struct Cell {
    float depth = 0.0f;
    float sent = 0.0f;     // the depth last sent
    bool queued = false;  // in queued_
  };
  void Press(const Eigen::Vector3d& point, float depth);
  soil_ruts_t Header(bool snapshot) const;

  bool has_surface_ = false;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero(), up_ = Eigen::Vector3d::UnitY(),
                  u_axis_ = Eigen::Vector3d::UnitX(), w_axis_ = Eigen::Vector3d::UnitZ();
  std::unordered_map<uint64_t, Cell> cells_;
  std::vector<uint64_t> queued_;
};

}  // namespace simpartner::sim
