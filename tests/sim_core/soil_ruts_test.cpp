// SoilRuts: the ruts' picture the sim sends the viewer (SIM_SOIL_RUTS):
// each wheel's tread stamped into 2 cm cells of the soil's surface (or of
// a heightfield's base plane), the cells deepened since the last message,
// every cell in bounded parts.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <set>
#include <utility>

#include "simpartner/sim/simulation.h"
#include "simpartner/sim/soil_ruts.h"
#include "soil_closed_forms.h"
#include "test_worlds.h"

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

// A world tilted 0.2 rad about z (gravity along -(-sin 0.2, cos 0.2, 0)):
// a 4 x 4 m heightfield of dry sand centred at (2, 0.5, -1.5), rising 0.1 m
// along x and z each (2 x 2 samples), and a wheel 0.3 m in radius, 0.2 m
// wide, its axle along the field's z, at field (0.7, -0.4) pressed 4 mm into
// the soil; `plane` adds a surface of the same sand 2 m below the field.
constexpr double kTilt = 0.2;
const Eigen::Vector3d kFieldAt(2.0, 0.5, -1.5);
const Eigen::Vector3d kWheelOnField(0.7, 0.0, -0.4);  // field frame; y from the field

Eigen::Matrix3d FieldTurn() {
  // y turned to (-sin, cos, 0): a turn by kTilt about z.
  return Eigen::AngleAxisd(kTilt, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// The field's height at (x, z) of its frame, worked out from its samples.
double FieldHeight(double x, double z) { return 0.1 * (x + 2.0) / 4.0 + 0.1 * (z + 2.0) / 4.0; }

std::string TiltedFieldWorld(bool plane) {
  const Eigen::Matrix3d r = FieldTurn();
  const Eigen::Vector3d wheel =
      kFieldAt + r * Eigen::Vector3d(kWheelOnField.x(),
                                     FieldHeight(kWheelOnField.x(), kWheelOnField.z()) + 0.3 - 0.004,
                                     kWheelOnField.z());
  std::string pose = "<transformation>";
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      pose += "<T" + std::to_string(i) + std::to_string(j) + ">" +
              std::to_string(j < 3 ? r(i, j) : wheel[i]) + "</T" + std::to_string(i) +
              std::to_string(j) + ">";
  pose += "</transformation>";
  const Eigen::Vector3d g = -9.81 * r.col(1);
  const Eigen::Vector3d below = kFieldAt - 2.0 * r.col(1);
  std::string surface;
  if (plane)
    surface = "<surface material=\"sand\"><a>" +
              std::to_string(r(0, 1)) + "</a><b>" + std::to_string(r(1, 1)) + "</b><c>0</c><d>" +
              std::to_string(below.dot(r.col(1))) + "</d></surface>";
  return R"(<world name="Tilted">)" + testing::Vec("gravity", g.x(), g.y(), g.z()) + surface +
         R"(<material name="sand"><mu>0.5</mu></material>
  <heightfield rows="2" columns="2" material="sand"><width>4</width><depth>4</depth>)" +
         testing::Vec("position", kFieldAt.x(), kFieldAt.y(), kFieldAt.z()) +
         R"(<samples>0 0.1 0.1 0.2</samples></heightfield>
  <object type="Cylinder" name="Wheel"><mass>50</mass><radius>0.3</radius><length>0.2</length>)" +
         pose + R"(</object>
</world>)";
}

model::World SandWorld(const std::string& xml) {
  model::World world = testing::LoadInline(xml);
  world.materials.at(0).soil = testing::WongEntry(1.1, 0.99, 1528.43, 1.04, 28);  // dry sand
  world.materials.at(0).soil->name = "dry_sand";
  return world;
}

// The rut's cells, put back in the world from the message alone (the
// field's base plane, its height there, the depth below it), lie under the
// wheel: across its tread, at its lowest point, as deep as it sank.
TEST(SoilRuts, AWheelOnATiltedFieldOffTheOriginLeavesCellsUnderIt) {
  Parameters params;
  params.stepsize = 0.001;
  // With a plane of the same soil 2 m below, which the engine evaluates
  // the wheel on too: the readout is of the field it pressed, and says so.
  Simulation sim(SandWorld(TiltedFieldWorld(true)), params, 1);
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(sim.Step());
  const std::vector<WheelSoilReadout> wheels = sim.engine().ReadWheelSoil();
  ASSERT_EQ(wheels.size(), 1u);
  const WheelSoilReadout& wheel = wheels[0];
  ASSERT_GT(wheel.sinkage, 0.001);
  EXPECT_EQ(wheel.ground, SoilGround::kHeightfield);

  const std::vector<soil_ruts_t> parts = sim.ruts().Snapshot();
  ASSERT_EQ(parts.size(), 1u);
  const soil_ruts_t& m = parts[0];
  EXPECT_EQ(m.ground, soil_ruts_t::GROUND_HEIGHTFIELD);
  const Eigen::Matrix3d r = FieldTurn();
  const Eigen::Vector3d origin(m.origin[0], m.origin[1], m.origin[2]);
  const Eigen::Vector3d up(m.up[0], m.up[1], m.up[2]), u_axis(m.u_axis[0], m.u_axis[1], m.u_axis[2]);
  // (The file gives gravity to 6 decimals.)
  EXPECT_LT((origin - kFieldAt).norm(), 1e-12);
  EXPECT_LT((up - r.col(1)).norm(), 1e-6);
  EXPECT_LT((u_axis - r.col(0)).norm(), 1e-6);
  // 0.2 m of tread in 2 cm cells: 10 or 11 across, one row or two along.
  EXPECT_GE(m.num_cells, 10);
  EXPECT_LE(m.num_cells, 22);
  const Eigen::Vector3d forward = wheel.axle.cross(up).normalized();
  // The field's slope along the wheel's up: the grid keeps depth along up.
  const double depth = wheel.sinkage / wheel.up.dot(up);
  for (size_t i = 0; i < m.depth.size(); ++i) {
    const Eigen::Vector3d base = origin + m.cell_size * ((m.u[i] + 0.5) * u_axis +
                                                         (m.w[i] + 0.5) * up.cross(u_axis));
    const Eigen::Vector3d local = r.transpose() * (base - kFieldAt);
    const Eigen::Vector3d floor =
        kFieldAt + r * Eigen::Vector3d(local.x(), FieldHeight(local.x(), local.z()), local.z()) -
        m.depth[i] * up;
    const Eigen::Vector3d off = floor - wheel.lowest_point;
    EXPECT_LE(std::abs(off.dot(wheel.axle)), 0.1 + m.cell_size) << "cell " << i;
    EXPECT_LE(std::abs(off.dot(forward)), m.cell_size) << "cell " << i;
    // Across the tread the floor follows the soil's slope (2.5 % along the
    // axle); from that line a cell's centre is within a cell of the
    // point pressed: 1 mm up or down on these slopes, at most.
    const Eigen::Vector3d across = (wheel.axle - wheel.axle.dot(wheel.up) * wheel.up).normalized();
    EXPECT_LE(std::abs((off - off.dot(across) * across).dot(up)), 0.001) << "cell " << i;
    EXPECT_NEAR(m.depth[i], depth, 1e-6) << "cell " << i;
  }
}

// With a plane and a heightfield of soil each ground has its grid: a
// wheel's cells go in the message of the ground the engine says it
// pressed, never the other's, and the changes of both go out in turn.
TEST(SoilRuts, EachSoilGroundKeepsItsOwnCells) {
  const model::World world = SandWorld(TiltedFieldWorld(true));
  SoilRuts ruts(world);
  const Eigen::Matrix3d r = FieldTurn();
  WheelSoilReadout on_plane;
  on_plane.sinkage = 0.02;
  on_plane.axle = r.col(2);
  on_plane.width = 0.2;
  on_plane.up = world.plane.head<3>();
  on_plane.surface_origin = world.plane[3] * on_plane.up;  // as the engine gives a plane
  on_plane.surface_u_axis = r.col(0);
  on_plane.lowest_point =
      kFieldAt - 0.005 * r.col(2) - 2.0 * on_plane.up - 0.02 * on_plane.up;
  WheelSoilReadout on_field = on_plane;
  on_field.ground = SoilGround::kHeightfield;
  on_field.up = r.col(1);
  on_field.surface_origin =
      kFieldAt + r * Eigen::Vector3d(0.7, FieldHeight(0.7, -0.405), -0.405);
  on_field.lowest_point = on_field.surface_origin - 0.03 * on_field.up;
  on_field.sinkage = 0.03;
  ruts.Stamp({on_plane, on_field});

  std::set<int8_t> grounds;
  for (int k = 0; k < 2; ++k) {
    ASSERT_TRUE(ruts.has_changes());
    const soil_ruts_t m = ruts.TakeChanges();
    grounds.insert(m.ground);
    EXPECT_EQ(m.num_cells, 11);
    for (float depth : m.depth)
      EXPECT_FLOAT_EQ(depth, m.ground == soil_ruts_t::GROUND_PLANE ? 0.02f : 0.03f);
  }
  EXPECT_EQ(grounds, (std::set<int8_t>{soil_ruts_t::GROUND_PLANE, soil_ruts_t::GROUND_HEIGHTFIELD}));
  EXPECT_FALSE(ruts.has_changes());
  const std::vector<soil_ruts_t> parts = ruts.Snapshot();
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_NE(parts[0].ground, parts[1].ground);
  // Without a heightfield of soil in the world a wheel said to be on one
  // leaves nothing.
  SoilRuts plane_only;
  plane_only.Stamp({on_field});
  EXPECT_FALSE(plane_only.has_changes());
  EXPECT_EQ(plane_only.cells(), 0u);
}

}  // namespace
}  // namespace simpartner::sim
