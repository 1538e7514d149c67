// SoilRuts: the ruts' picture the sim sends the viewer (SIM_SOIL_RUTS):
// each wheel's tread stamped into 2 cm cells of the soil's surface, the
// cells deepened since the last message, every cell in bounded parts.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "simpartner/sim/soil_ruts.h"

namespace simpartner::sim {
namespace {

// A wheel 0.2 m wide with its axle along z on a y-up surface through the
// origin (grid axes: u along x, w along y x x = -z), its lowest rim point
// `sinkage` below the surface at x, z.
WheelSoilReadout WheelAt(double x, double z, double sinkage) {
  WheelSoilReadout wheel;
  wheel.body = 3;
  wheel.sinkage = sinkage;
  wheel.axle = Eigen::Vector3d::UnitZ();
  wheel.width = 0.2;
  wheel.lowest_point = Eigen::Vector3d(x, -sinkage, z);
  wheel.up = Eigen::Vector3d::UnitY();
  wheel.surface_u_axis = Eigen::Vector3d::UnitX();
  return wheel;
}

std::set<std::pair<int32_t, int32_t>> CellsOf(const soil_ruts_t& m) {
  std::set<std::pair<int32_t, int32_t>> cells;
  for (int32_t i = 0; i < m.num_cells; ++i) cells.insert({m.u[static_cast<size_t>(i)], m.w[static_cast<size_t>(i)]});
  return cells;
}

TEST(SoilRuts, AWheelPressesARowOfCellsAcrossItsTread) {
  SoilRuts ruts;
  // Centred at z = 0.505: the tread spans z 0.405 .. 0.605, cells w = -21 .. -31.
  ruts.Stamp({WheelAt(1.01, 0.505, 0.03)});
  const soil_ruts_t m = ruts.TakeChanges();
  EXPECT_FALSE(m.snapshot);
  EXPECT_EQ(m.part, 0);
  EXPECT_EQ(m.parts, 1);
  EXPECT_EQ(m.cell_size, 0.02);
  EXPECT_EQ(m.up[1], 1.0);
  EXPECT_EQ(m.u_axis[0], 1.0);
  std::set<std::pair<int32_t, int32_t>> expected;
  for (int32_t w = -31; w <= -21; ++w) expected.insert({50, w});
  EXPECT_EQ(CellsOf(m), expected);
  for (float depth : m.depth) EXPECT_FLOAT_EQ(depth, 0.03f);
  EXPECT_FALSE(ruts.has_changes());
}

TEST(SoilRuts, OnlyCellsDeepenedByHalfAMillimetreAreSentAgain) {
  SoilRuts ruts;
  ruts.Stamp({WheelAt(1.01, 0.505, 0.03)});
  ruts.TakeChanges();
  ruts.Stamp({WheelAt(1.01, 0.505, 0.0302)});  // 0.2 mm deeper
  EXPECT_FALSE(ruts.has_changes());
  ruts.Stamp({WheelAt(1.01, 0.505, 0.0299)});  // shallower: the rut stays
  EXPECT_FALSE(ruts.has_changes());
  ruts.Stamp({WheelAt(1.01, 0.505, 0.031)});
  const soil_ruts_t m = ruts.TakeChanges();
  EXPECT_EQ(m.num_cells, 11);
  for (float depth : m.depth) EXPECT_FLOAT_EQ(depth, 0.031f);
  // A wheel on rigid ground or above the soil leaves nothing.
  ruts.Stamp({WheelAt(3.01, 0.505, 0.0)});
  EXPECT_FALSE(ruts.has_changes());
}

TEST(SoilRuts, MessagesAndSnapshotsAreBounded) {
  SoilRuts ruts;
  // Five 4 m tracks side by side: 200 cells long, 11 across each, 11,000
  // cells: more than a message holds.
  std::vector<WheelSoilReadout> tracks;
  for (int lane = 0; lane < 5; ++lane)
    for (int k = 0; k < 400; ++k) tracks.push_back(WheelAt(0.005 + 0.01 * k, 0.505 + 0.22 * lane, 0.02));
  ruts.Stamp(tracks);
  ASSERT_EQ(ruts.cells(), 11000u);
  const soil_ruts_t first = ruts.TakeChanges();
  EXPECT_EQ(first.num_cells, SoilRuts::kCellsPerMessage);
  EXPECT_TRUE(ruts.has_changes());
  const soil_ruts_t second = ruts.TakeChanges();
  EXPECT_EQ(second.num_cells, 11000 - SoilRuts::kCellsPerMessage);
  EXPECT_FALSE(ruts.has_changes());

  const std::vector<soil_ruts_t> parts = ruts.Snapshot();
  ASSERT_EQ(parts.size(), 2u);
  std::set<std::pair<int32_t, int32_t>> all;
  for (size_t i = 0; i < parts.size(); ++i) {
    EXPECT_TRUE(parts[i].snapshot);
    EXPECT_EQ(parts[i].part, static_cast<int32_t>(i));
    EXPECT_EQ(parts[i].parts, 2);
    EXPECT_LE(parts[i].num_cells, SoilRuts::kCellsPerMessage);
    const auto cells = CellsOf(parts[i]);
    all.insert(cells.begin(), cells.end());
  }
  EXPECT_EQ(all.size(), 11000u);
  ruts.Clear();
  EXPECT_EQ(ruts.Snapshot()[0].num_cells, 0);
}

}  // namespace
}  // namespace simpartner::sim
