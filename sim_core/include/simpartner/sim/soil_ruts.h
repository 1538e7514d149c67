// The ruts wheels press into soft soil, as the viewer draws them (issue
// 28, docs/soil.md): on a grid of kCellSize cells of each soil ground (the
// surface plane's, the heightfield's base plane), the deepest sinkage a
// wheel's lowest rim point reached, stamped across its tread. Fed each
// step's wheel readouts; gives SIM_SOIL_RUTS messages: the cells deepened
// since the last one, or every cell.
// The soil's own memory (2 mm cells along each wheel's mid-plane) stays
// the engine's: this is its picture, coarse enough to draw and to send.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "simpartner/model/model.h"
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

  // A world whose only soil is its surface plane. The plane's grid lies
  // on the surface the first wheel on it reports.
  SoilRuts() = default;
  // The soil grounds of `world`: its surface plane, and its heightfield
  // where that is of soil (its grid lies on the field's base plane).
  explicit SoilRuts(const model::World& world);

  // Stamps each wheel's tread into the grid of the ground the engine says
  // it pressed; a wheel on a heightfield is left out when the world's
  // heightfield is not of soil.
  void Stamp(const std::vector<WheelSoilReadout>& wheels);
  void Clear();

  bool has_changes() const;
  size_t cells() const;
  bool full() const { return cells() >= kMaxCells; }

  // The cells of one ground deepened since the last call (at most
  // kCellsPerMessage; the rest, and the other ground's, come with the
  // next), as a message without utime, simulation id and step.
  soil_ruts_t TakeChanges();
  // Every cell, each ground's in its own parts of at most
  // kCellsPerMessage (one empty part when there are none).
  std::vector<soil_ruts_t> Snapshot() const;

 private:
  struct Cell {
    float depth = 0.0f;
    float sent = 0.0f;     // the depth last sent
    bool queued = false;  // in queued
  };
  // One ground's cells, keyed along u_axis and w_axis = up x u_axis from
  // origin.
  struct Grid {
    explicit Grid(int8_t ground_kind) : ground(ground_kind) {}
    int8_t ground;
    bool has_frame = false;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero(), up = Eigen::Vector3d::UnitY(),
                    u_axis = Eigen::Vector3d::UnitX(), w_axis = Eigen::Vector3d::UnitZ();
    std::unordered_map<uint64_t, Cell> cells;
    std::vector<uint64_t> queued;
  };
  // The grid of the ground `wheel` pressed (its frame set), or null.
  Grid* GridOf(const WheelSoilReadout& wheel);
  void Press(Grid* grid, const Eigen::Vector3d& point, float depth);
  soil_ruts_t Header(const Grid& grid, bool snapshot) const;

  // Indexed by soil_ruts_t::GROUND_*.
  std::array<Grid, 2> grids_ = {Grid(soil_ruts_t::GROUND_PLANE),
                                 Grid(soil_ruts_t::GROUND_HEIGHTFIELD)};
  size_t next_grid_ = 0;       // whose changes TakeChanges sends first
};

}  // namespace simpartner::sim
