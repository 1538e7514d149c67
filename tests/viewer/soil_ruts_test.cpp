// The soil's ruts in the viewer (SIM_SOIL_RUTS): kept for the simulation
// shown, snapshots replacing and changes deepening them, forged messages
// refused with channel, field and value, and drawn as lowered, darker
// patches of the ground seen through their openings.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/viewer/bus.h"
#include "simpartner/viewer/scene.h"
#include "simpartner/viewer/soil_ruts.h"
#include "simpartner/status_t.hpp"
#include "viewer_messages.h"

namespace simpartner::viewer {
namespace {

using testing::TwoBodyModel;

struct Cell {
  int32_t u, w;
  float depth;
};

// Ruts on the y-up plane through the origin, grid axis u along x, 2 cm cells.
soil_ruts_t Ruts(int64_t simulation_id, bool snapshot, const std::vector<Cell>& cells) {
  soil_ruts_t m{};
  m.simulation_id = simulation_id;
  m.step = 100;
  m.snapshot = snapshot;
  m.part = 0;
  m.parts = 1;
  m.up[1] = 1;
  m.u_axis[0] = 1;
  m.cell_size = 0.02;
  for (const Cell& c : cells) {
    m.u.push_back(c.u);
    m.w.push_back(c.w);
    m.depth.push_back(c.depth);
  }
  m.num_cells = static_cast<int32_t>(cells.size());
  return m;
}

float DepthAt(const Scene& scene, int32_t u, int32_t w) {
  const auto it = scene.ruts().depths().find({u, w});
  return it == scene.ruts().depths().end() ? 0.0f : it->second;
}

TEST(SoilRutsTest, SnapshotsReplaceTheRutsAndChangesDeepenThem) {
  Scene scene;
  ASSERT_TRUE(scene.OfferModel(TwoBodyModel(7)).accepted);
  ASSERT_TRUE(scene.OfferSoilRuts(Ruts(7, true, {{1, 2, 0.01f}, {1, 3, 0.02f}})).accepted);
  EXPECT_EQ(scene.ruts().cells(), 2u);
  // A change deepens a cell, adds one, and never makes one shallower (a
  // change that arrived late).
  ASSERT_TRUE(scene.OfferSoilRuts(Ruts(7, false, {{1, 2, 0.03f}, {1, 3, 0.01f}, {5, 5, 0.04f}})).accepted);
  EXPECT_EQ(scene.ruts().cells(), 3u);
  EXPECT_EQ(DepthAt(scene, 1, 2), 0.03f);
  EXPECT_EQ(DepthAt(scene, 1, 3), 0.02f);
  EXPECT_EQ(DepthAt(scene, 5, 5), 0.04f);
  EXPECT_FLOAT_EQ(static_cast<float>(scene.ruts().deepest()), 0.04f);
  // The cell's centre on the untouched surface: w runs along up x u = -z.
  EXPECT_TRUE(scene.ruts().CellCentre(5, 5).isApprox(Eigen::Vector3d(0.11, 0, -0.11)));
  // A snapshot is every cell: the rest go.
  ASSERT_TRUE(scene.OfferSoilRuts(Ruts(7, true, {{9, 9, 0.05f}})).accepted);
  EXPECT_EQ(scene.ruts().cells(), 1u);
  EXPECT_EQ(DepthAt(scene, 9, 9), 0.05f);
  // A new simulation (the sim was reset: its status said so) has no ruts
  // until it sends them.
  status_t reset{};
  reset.simulation_id = 7;
  reset.run_state = status_t::RUN_RESET;
  scene.OfferStatus(reset);
  ASSERT_TRUE(scene.OfferModel(TwoBodyModel(8)).accepted);
  EXPECT_EQ(scene.ruts().cells(), 0u);
  EXPECT_EQ(scene.rejected_total(), 0);
}

TEST(SoilRutsTest, RutsOfAnotherSimulationOrBeforeTheModelAreNotShown) {
  Scene scene;
  const Verdict early = scene.OfferSoilRuts(Ruts(7, false, {{1, 2, 0.01f}}));
  EXPECT_FALSE(early.accepted);
  EXPECT_TRUE(early.want_model);  // the model's answer brings the ruts again
  EXPECT_EQ(scene.rejected_total(), 0);
  scene.OfferModel(TwoBodyModel(7));
  const Verdict other = scene.OfferSoilRuts(Ruts(8, false, {{1, 2, 0.01f}}));
  ASSERT_TRUE(other.problem.has_value());
  EXPECT_EQ(other.problem->kind, Rejection::kOtherSimulation);
  EXPECT_EQ(other.problem->message.rfind("SIM_SOIL_RUTS: simulation_id = 8", 0), 0u)
      << other.problem->message;
  EXPECT_EQ(scene.ruts().cells(), 0u);
}

TEST(SoilRutsTest, ForgedRutsAreRefusedNamingTheFieldAndValue) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  Scene scene;
  scene.OfferModel(TwoBodyModel(7));
  ASSERT_TRUE(scene.OfferSoilRuts(Ruts(7, true, {{1, 2, 0.01f}})).accepted);
  struct Case {
    soil_ruts_t message;
    std::string expected;
  };
  std::vector<Case> cases;
  cases.push_back({Ruts(7, false, {{1, 2, 0.02f}, {3, 4, -0.5f}}),
                   "SIM_SOIL_RUTS: depth[1] = -0.5 (cell 3, 4; 0 < depth <= 10 m)"});
  cases.push_back({Ruts(7, false, {{3, 4, 11.0f}}), "depth[0] = 11 (cell 3, 4"});
  cases.push_back({Ruts(7, false, {{3, 4, static_cast<float>(kNaN)}}), "depth[0] = nan"});
  Case origin{Ruts(7, false, {{3, 4, 0.01f}}), "SIM_SOIL_RUTS: origin = (nan, 0, 0)"};
  origin.message.origin[0] = kNaN;
  cases.push_back(origin);
  Case up{Ruts(7, false, {{3, 4, 0.01f}}), "up = (0, 2, 0) is not a unit vector"};
  up.message.up[1] = 2;
  cases.push_back(up);
  Case axis{Ruts(7, false, {{3, 4, 0.01f}}), "u_axis = (0, 1, 0) is not along the surface"};
  axis.message.u_axis[0] = 0;
  axis.message.u_axis[1] = 1;
  cases.push_back(axis);
  Case cell{Ruts(7, false, {{3, 4, 0.01f}}), "cell_size = 0 (1 mm to 1 m)"};
  cell.message.cell_size = 0;
  cases.push_back(cell);
  Case part{Ruts(7, true, {{3, 4, 0.01f}}), "part = 2 of parts = 2"};
  part.message.part = 2;
  part.message.parts = 2;
  cases.push_back(part);
  int64_t refused = 0;
  for (const Case& c : cases) {
    const Verdict v = scene.OfferSoilRuts(c.message);
    EXPECT_FALSE(v.accepted) << c.expected;
    ASSERT_TRUE(v.problem.has_value()) << c.expected;
    EXPECT_EQ(v.problem->kind, Rejection::kBadRuts);
    EXPECT_EQ(v.problem->channel, "SIM_SOIL_RUTS");
    EXPECT_NE(v.problem->message.find(c.expected), std::string::npos) << v.problem->message;
    EXPECT_NE(v.problem->message.find("(step 100): ignored"), std::string::npos) << v.problem->message;
    EXPECT_EQ(scene.rejected(Rejection::kBadRuts), ++refused);
  }
  // What was shown stays.
  EXPECT_EQ(scene.ruts().cells(), 1u);
  EXPECT_EQ(DepthAt(scene, 1, 2), 0.01f);
  EXPECT_NE(scene.RejectionSummary().find("bad ruts"), std::string::npos);
}

TEST(SoilRutsTest, TheBusTakesRutsAndReportsAForgedMessage) {
  lcm::LCM lcm("memq://");
  Scene scene;
  std::vector<std::string> reports;
  ViewerBus bus(&lcm, "memq://", &scene, [&](const std::string& m) { reports.push_back(m); });
  const model_t model = TwoBodyModel(7);
  lcm.publish(channels::kModel, &model);
  const soil_ruts_t good = Ruts(7, true, {{1, 2, 0.01f}, {1, 3, 0.02f}});
  lcm.publish(channels::kSoilRuts, &good);
  soil_ruts_t forged = Ruts(7, false, {{4, 4, 0.01f}});
  forged.cell_size = -1;
  lcm.publish(channels::kSoilRuts, &forged);
  bus.Drain(std::chrono::steady_clock::now());
  EXPECT_EQ(scene.ruts().cells(), 2u);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0], "SIM_SOIL_RUTS: cell_size = -1 (1 mm to 1 m) (step 100): ignored");
}

TEST(SoilRutsTest, TheRutsAreAGaplessTroughLoweredIntoTheGroundAndDarker) {
  // A 3 x 3 patch 4 cm deep and a lone cell 8 cm deep.
  std::vector<Cell> cells = {{10, 10, 0.08f}};
  for (int32_t u = 0; u < 3; ++u)
    for (int32_t w = 0; w < 3; ++w) cells.push_back({u, w, 0.04f});
  RutMap ruts;
  ruts.Take(Ruts(7, true, cells));
  const Eigen::Vector3f ground(0.5f, 0.55f, 0.5f);
  const Mesh mesh = RutMesh(ruts, ground);
  ASSERT_EQ(mesh.positions.size(), 4u * 10);
  ASSERT_EQ(mesh.indices.size(), 6u * 10);
  ASSERT_EQ(mesh.colors.size(), 4u * 10);
  // Corners: x = 0.02 u, z = -0.02 w (w runs along up x u = -z).
  auto corner_y = [&](float x, float z) {
    std::vector<float> ys;
    for (const Eigen::Vector3f& p : mesh.positions)
      if (std::abs(p.x() - x) < 1e-6f && std::abs(p.z() - z) < 1e-6f) ys.push_back(p.y());
    return ys;
  };
  // Inside the patch the floor is 4 cm down, each inner corner shared by
  // the four cells around it at the same height: no gaps.
  for (float x : {0.02f, 0.04f})
    for (float z : {-0.02f, -0.04f}) {
      const std::vector<float> ys = corner_y(x, z);
      ASSERT_EQ(ys.size(), 4u) << x << ", " << z;
      for (float y : ys) EXPECT_NEAR(y, -0.04f, 1e-6f) << x << ", " << z;
    }
  // The patch's edges slope up: an edge corner (two cells) 2 cm down, an
  // outer corner (one cell) 1 cm; the lone cell's corners a quarter of it.
  for (float y : corner_y(0.02f, 0.0f)) EXPECT_NEAR(y, -0.02f, 1e-6f);
  for (float y : corner_y(0.0f, 0.0f)) EXPECT_NEAR(y, -0.01f, 1e-6f);
  for (float y : corner_y(0.2f, -0.2f)) EXPECT_NEAR(y, -0.02f, 1e-6f);
  for (size_t t = 0; t < mesh.triangles(); ++t) {
    const Eigen::Vector3f a = mesh.positions[mesh.Corner(t, 0)];
    const Eigen::Vector3f b = mesh.positions[mesh.Corner(t, 1)];
    const Eigen::Vector3f c = mesh.positions[mesh.Corner(t, 2)];
    EXPECT_GT((b - a).cross(c - a).y(), 0.0f) << "triangle " << t << " faces down";
    EXPECT_GT(mesh.normals[mesh.Corner(t, 0)].y(), 0.5f);
  }
  // Darker than the ground by a third and more, by half at 5 cm and
  // deeper: the lone cell (x 0.2 .. 0.22) at half, the patch's between.
  for (size_t k = 0; k < mesh.colors.size(); ++k) {
    const float shade = mesh.colors[k].x() / ground.x();
    if (mesh.positions[k].x() > 0.19f) {
      EXPECT_NEAR(shade, 0.5f, 1e-5f);
    } else {
      EXPECT_GT(shade, 0.5f);
      EXPECT_LT(shade, 0.67f);
    }
  }
}

// TwoBodyModel tilted 0.2 rad about z, without its plane, over a 4 x 4 m
// heightfield centred at (2, 0.5, -1.5) rising 0.1 m along x and z each
// (2 x 2 samples): its surface is the plane h = 0.025 (x + 2) + 0.025 (z + 2)
// of its frame, whichever diagonal its triangles take.
model_t TiltedFieldModel(int64_t simulation_id) {
  model_t m = TwoBodyModel(simulation_id);
  m.has_plane = false;
  m.up[0] = -std::sin(0.2);
  m.up[1] = std::cos(0.2);
  m.gravity[0] = -9.81 * m.up[0];
  m.gravity[1] = -9.81 * m.up[1];
  heightfield_t& h = m.heightfield;
  h.present = true;
  h.rows = h.columns = 2;
  h.width = h.depth = 4;
  h.scale = 1;
  h.thickness = 1;
  h.position[0] = 2;
  h.position[1] = 0.5;
  h.position[2] = -1.5;
  h.samples = {0.0f, 0.1f, 0.1f, 0.2f};
  h.num_samples = 4;
  return m;
}

Eigen::Matrix3d TiltedFieldTurn() {
  // y turned to (-sin 0.2, cos 0.2, 0): a turn by 0.2 rad about z.
  return Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// Ruts on the tilted field's grid: its base plane, in its frame.
soil_ruts_t FieldRuts(int64_t simulation_id, const std::vector<Cell>& cells) {
  soil_ruts_t m = Ruts(simulation_id, true, cells);
  const Eigen::Matrix3d r = TiltedFieldTurn();
  m.ground = soil_ruts_t::GROUND_HEIGHTFIELD;
  m.origin[0] = 2;
  m.origin[1] = 0.5;
  m.origin[2] = -1.5;
  for (int i = 0; i < 3; ++i) {
    m.up[i] = r(i, 1);
    m.u_axis[i] = r(i, 0);
  }
  return m;
}

// On a heightfield each corner is lowered from the field's surface above
// it, not from its base plane, along the field's up.
TEST(SoilRutsTest, RutsOnAHeightfieldAreLoweredFromItsSurface) {
  Scene scene;
  scene.OfferModel(TiltedFieldModel(7));
  // A lone cell 2 cm deep at field (1.01, -0.51) (w runs along -z): each
  // corner a quarter of it down.
  ASSERT_TRUE(scene.OfferSoilRuts(FieldRuts(7, {{50, 25, 0.02f}})).accepted);
  const RutMap& ruts = scene.ruts(soil_ruts_t::GROUND_HEIGHTFIELD);
  ASSERT_EQ(ruts.cells(), 1u);
  EXPECT_EQ(scene.ruts().cells(), 0u);  // the plane's are apart
  const Mesh mesh = RutMesh(ruts, Eigen::Vector3f(0.5f, 0.5f, 0.5f), &scene.model().heightfield);
  ASSERT_EQ(mesh.positions.size(), 4u);
  const Eigen::Matrix3d r = TiltedFieldTurn();
  const Eigen::Vector3d at(2, 0.5, -1.5);
  for (const Eigen::Vector3f& p : mesh.positions) {
    const Eigen::Vector3d local = r.transpose() * (p.cast<double>() - at);
    EXPECT_TRUE(std::abs(local.x() - 1.0) < 1e-5 || std::abs(local.x() - 1.02) < 1e-5) << local.x();
    EXPECT_TRUE(std::abs(local.z() + 0.5) < 1e-5 || std::abs(local.z() + 0.52) < 1e-5) << local.z();
    const double surface = 0.025 * (local.x() + 2) + 0.025 * (local.z() + 2);
    EXPECT_NEAR(local.y(), surface - 0.005, 1e-5);
  }
  // Its opening, which the renderer draws the floor through (so that a
  // hill before it hides it), is the same square on the field's surface.
  const Mesh opening = RutOpeningMesh(ruts, &scene.model().heightfield);
  ASSERT_EQ(opening.positions.size(), 4u);
  ASSERT_EQ(opening.indices, mesh.indices);
  ASSERT_EQ(opening.normals.size(), 4u);
  ASSERT_EQ(opening.colors.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    const Eigen::Vector3d local = r.transpose() * (opening.positions[k].cast<double>() - at);
    const Eigen::Vector3d floor = r.transpose() * (mesh.positions[k].cast<double>() - at);
    EXPECT_NEAR(local.x(), floor.x(), 1e-5);
    EXPECT_NEAR(local.z(), floor.z(), 1e-5);
    EXPECT_NEAR(local.y(), 0.025 * (local.x() + 2) + 0.025 * (local.z() + 2), 1e-5);
  }
}

// Ruts never go where their message does not put them on a ground of the
// model: another ground, a frame that is not the ground's, an unknown one.
TEST(SoilRutsTest, RutsOnAGroundTheModelLacksOrElsewhereAreRefused) {
  Scene scene;
  scene.OfferModel(TiltedFieldModel(7));
  struct Case {
    soil_ruts_t message;
    std::string expected;
  };
  std::vector<Case> cases;
  cases.push_back({Ruts(7, false, {{1, 2, 0.01f}}),
                   "SIM_SOIL_RUTS: ground = 0 but the model has no surface plane (step 100)"});
  Case moved{FieldRuts(7, {{1, 2, 0.01f}}), "origin = (2, 0.6, -1.5), up = "};
  moved.message.origin[1] = 0.6;
  cases.push_back(moved);
  Case turned{FieldRuts(7, {{1, 2, 0.01f}}), "are not the heightfield's frame"};
  turned.message.up[0] = 0;
  turned.message.up[1] = 1;
  turned.message.u_axis[0] = 1;
  turned.message.u_axis[1] = 0;
  cases.push_back(turned);
  Case unknown{FieldRuts(7, {{1, 2, 0.01f}}), "ground = 7 (0 the plane, 1 the heightfield)"};
  unknown.message.ground = 7;
  cases.push_back(unknown);
  for (const Case& c : cases) {
    const Verdict v = scene.OfferSoilRuts(c.message);
    EXPECT_FALSE(v.accepted) << c.expected;
    ASSERT_TRUE(v.problem.has_value()) << c.expected;
    EXPECT_EQ(v.problem->channel, "SIM_SOIL_RUTS");
    EXPECT_NE(v.problem->message.find(c.expected), std::string::npos) << v.problem->message;
  }
  EXPECT_EQ(scene.ruts(soil_ruts_t::GROUND_HEIGHTFIELD).cells(), 0u);
  // On the plane of a model without a heightfield, ground 1 is refused too.
  Scene flat;
  flat.OfferModel(TwoBodyModel(7));
  const Verdict v = flat.OfferSoilRuts(FieldRuts(7, {{1, 2, 0.01f}}));
  ASSERT_TRUE(v.problem.has_value());
  EXPECT_NE(v.problem->message.find("ground = 1 but the model has no heightfield"), std::string::npos)
      << v.problem->message;
}

}  // namespace
}  // namespace simpartner::viewer
