// The MuJoCo engine (--engine=mujoco) against closed forms: the same
// worlds, readouts and expected values as the ODE engine's physics tests,
// and what only this engine has to get right (its frame mapping, motors,
// anisotropic friction, bounce, heightfield, refusals).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>

#include "simpartner/sim/engine.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::Command;
using testing::MakeSim;
using testing::Transform;
using testing::Vec;

constexpr double kG = 9.81;

Parameters Mujoco() {
  Parameters params;
  params.engine = "mujoco";
  return params;
}

// The closed-form tests run on both engines: the expected values are the
// physics', not either engine's.
class BothEngines : public ::testing::TestWithParam<const char*> {
 protected:
  Parameters Params() const {
    Parameters params;
    params.engine = GetParam();
    return params;
  }
};
INSTANTIATE_TEST_SUITE_P(Engines, BothEngines, ::testing::Values("ode", "mujoco"));

// A wheel (cylinder r 0.2 m, 1 kg, axis z) on a hinge to the world about
// z, no actuator, no gravity: inertia about the axle m r^2 / 2 = 0.02.
std::string FreeWheelWorld() {
  return "<world><gravity><x>0</x><y>0</y><z>0</z></gravity>"
         "<object type=\"Cylinder\" name=\"Wheel\"><mass>1</mass><radius>0.2</radius>"
         "<length>0.1</length>" +
         Transform(0, 1, 0) +
         "</object><joint type=\"Hinge\" name=\"Axle\"><body1>Wheel</body1><body2>world</body2>"
         "<anchor><x>0</x><y>1</y><z>0</z></anchor><axis1><x>0</x><y>0</y><z>1</z></axis1>"
         "</joint></world>";
}

const char* kGround = "<surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>";

std::string ParticleWorld(double height, double vx, double vz) {
  return "<world name=\"Fall\"><object type=\"Body\" name=\"P\"><mass>1</mass>" +
         Transform(0, height, 0) + "<translationalVelocity><vx>" + std::to_string(vx) +
         "</vx><vy>0</vy><vz>" + std::to_string(vz) +
         "</vz></translationalVelocity></object></world>";
}

TEST(MujocoEngine, IsTheEngineTheParameterNames) {
  auto sim = MakeSim(ParticleWorld(10, 0, 0), {}, Mujoco());
  EXPECT_STREQ(sim->engine().name(), "mujoco");
  auto ode = MakeSim(ParticleWorld(10, 0, 0));
  EXPECT_STREQ(ode->engine().name(), "ode");
}

// Semi-implicit Euler, as ODE: after n steps y = h0 - g dt^2 n (n + 1) / 2.
TEST_P(BothEngines, FreeFallIsSemiImplicitEuler) {
  auto sim = MakeSim(ParticleWorld(500, 3, -2), {}, Params());
  const double dt = 0.001;
  double worst = 0.0;
  for (int n = 1; n <= 3000; ++n) {
    ASSERT_TRUE(sim->Step());
    const BodyReadout b = sim->engine().ReadBody(0);
    worst = std::max(worst, std::abs(b.position.y() - (500.0 - kG * dt * dt * n * (n + 1) / 2.0)));
    worst = std::max(worst, std::abs(b.position.x() - 3.0 * dt * n));
    worst = std::max(worst, std::abs(b.position.z() + 2.0 * dt * n));
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(sim->engine().ReadBody(0).linear_velocity.y(), -kG * 3.0, 1e-9);
}

TEST_P(BothEngines, RestingSphereCarriesItsWeight) {
  const std::string world = std::string("<world>") + kGround +
                            "<object type=\"Sphere\" name=\"Ball\"><mass>2</mass><radius>0.5"
                            "</radius>" +
                            Transform(0, 0.5, 0) + "</object></world>";
  auto sim = MakeSim(world, {}, Params());
  for (int n = 0; n < 2000; ++n) ASSERT_TRUE(sim->Step());
  const BodyReadout b = sim->engine().ReadBody(0);
  EXPECT_NEAR(b.contact_force.y(), 2 * kG, 1e-3);
  EXPECT_NEAR(b.contact_force.x(), 0.0, 1e-6);
  EXPECT_NEAR(b.position.y(), 0.5, 2e-3);
  EXPECT_LT(b.linear_velocity.norm(), 1e-4);
}

TEST_P(BothEngines, ContactForceOnEveryBodyOnGroundOrOnAStaticBox) {
  std::string world = std::string("<world>") + kGround;
  for (int k = 0; k < 3; ++k) {
    const double x = 3.0 * k;
    world += "<object type=\"Box\" name=\"Table" + std::to_string(k) +
             "\" static=\"true\"><size><x>1</x><y>1</y><z>1</z></size>" + Transform(x, 0.5, 5) +
             "</object><object type=\"Sphere\" name=\"OnTable" + std::to_string(k) + "\"><mass>" +
             std::to_string(k + 1) + "</mass><radius>0.25</radius>" + Transform(x, 1.25, 5) +
             "</object><object type=\"Box\" name=\"OnGround" + std::to_string(k) + "\"><mass>" +
             std::to_string(k + 1) + "</mass>" + Vec("size", 0.5, 0.5, 0.5) +
             Transform(x, 0.25, 0) + "</object>";
  }
  world += "</world>";
  auto sim = MakeSim(world, {}, Params());
  for (int n = 0; n < 2000; ++n) ASSERT_TRUE(sim->Step());
  for (int i = 0; i < static_cast<int>(sim->flat().bodies.size()); ++i) {
    if (sim->flat().bodies[i].source->is_static) continue;
    const double weight = sim->flat().bodies[i].source->mass * kG;
    EXPECT_NEAR(sim->engine().ReadBody(i).contact_force.y(), weight, 1e-3 * weight)
        << sim->flat().bodies[i].name;
  }
}

// A box pushed along the ground at v0 slides to rest after v0^2 / (2 mu g).
TEST_P(BothEngines, SlidingBoxStopsAfterCoulombsDistance) {
  for (const double heading : {0.0, 0.7}) {
    Parameters params = Params();
    params.contactMu = 0.5;
    const double v0 = 2.0;
    const std::string world =
        std::string("<world>") + kGround + "<object type=\"Box\" name=\"Cube\"><mass>3</mass>" +
        Vec("size", 0.4, 0.4, 0.4) + Transform(0, 0.2, 0) + "<translationalVelocity><vx>" +
        std::to_string(v0 * std::cos(heading)) + "</vx><vy>0</vy><vz>" +
        std::to_string(v0 * std::sin(heading)) + "</vz></translationalVelocity></object></world>";
    auto sim = MakeSim(world, {}, params);
    for (int n = 0; n < 2000; ++n) ASSERT_TRUE(sim->Step());
    const BodyReadout b = sim->engine().ReadBody(0);
    const double expected = v0 * v0 / (2 * 0.5 * kG);
    EXPECT_NEAR(Eigen::Vector2d(b.position.x(), b.position.z()).norm(), expected, 0.01 * expected)
        << "heading " << heading;
    EXPECT_LT(b.linear_velocity.norm(), 1e-3);
  }
}

// A pendulum pinned to the world: the joint holds the hanging bob up.
TEST_P(BothEngines, JointToTheWorldReportsTheForceOnItsBody) {
  const std::string world =
      "<world><object type=\"Sphere\" name=\"Bob\"><mass>2</mass><radius>0.1</radius>" +
      Transform(0, 1, 0) +
      "</object><joint type=\"Ball\" name=\"Pin\"><body1>world</body1><body2>Bob</body2>"
      "<anchor><x>0</x><y>2</y><z>0</z></anchor></joint></world>";
  auto sim = MakeSim(world, {}, Params());
  for (int n = 0; n < 500; ++n) ASSERT_TRUE(sim->Step());
  const JointReadout j = sim->engine().ReadJoint(0);
  EXPECT_NEAR(j.force2.y(), 2 * kG, 1e-3);
  EXPECT_NEAR(j.force1.norm(), 0.0, 1e-12);
  EXPECT_NEAR(j.anchor.y(), 2.0, 1e-9);
}

// A hinge pendulum released at 90 degrees: its angle follows the closed
// form of small steps (energy: omega at the bottom = sqrt(2 g / l) for a
// point mass at l).
TEST_P(BothEngines, HingeAngleAndRateCountBody1RelativeToBody2) {
  const double l = 1.0;
  for (const bool world_first : {true, false}) {
    const std::string pin = world_first ? "<body1>world</body1><body2>Bob</body2>"
                                        : "<body1>Bob</body1><body2>world</body2>";
    const std::string world =
        "<world><object type=\"Body\" name=\"Bob\"><mass>1</mass>" + Transform(l, 2, 0) +
        "</object><joint type=\"Hinge\" name=\"Pin\">" + pin +
        "<anchor><x>0</x><y>2</y><z>0</z></anchor><axis1><x>0</x><y>0</y><z>1</z></axis1>"
        "</joint></world>";
    auto sim = MakeSim(world, {}, Params());
    double fastest = 0.0, angle_at_fastest = 0.0;
    for (int n = 0; n < 1200; ++n) {
      ASSERT_TRUE(sim->Step());
      const double rate = sim->engine().JointRate(0, 0);
      if (std::abs(rate) > std::abs(fastest)) {
        fastest = rate;
        angle_at_fastest = sim->engine().JointPosition(0, 0);
      }
    }
    // Falling from +x to -y turns the bob by -90 degrees about +z, the
    // world by +90 degrees relative to the bob; ours counts body1
    // relative to body2.
    const double sign = world_first ? 1.0 : -1.0;
    EXPECT_NEAR(fastest, sign * std::sqrt(2 * kG / l), 0.01 * std::sqrt(2 * kG / l));
    EXPECT_NEAR(angle_at_fastest, sign * M_PI / 2, 0.02);
  }
}

// ODE's motor: the axis reaches its velocity (a free wheel: within a
// step) and, asked for more than its force limit gives, pushes with the
// limit: 0.1 N m on 0.02 kg m^2 is 5 rad/s^2.
TEST_P(BothEngines, MotorReachesItsVelocityAndPushesWithItsLimitBeyond) {
  auto sim = MakeSim(FreeWheelWorld(), {}, Params());
  sim->engine().SetMotor(0, 0, 5.0, 1000.0);
  ASSERT_TRUE(sim->Step());
  ASSERT_TRUE(sim->Step());
  EXPECT_NEAR(sim->engine().JointRate(0, 0), 5.0, 0.05);
  sim->engine().SetMotor(0, 0, 100.0, 0.1);
  for (int n = 0; n < 1000; ++n) ASSERT_TRUE(sim->Step());
  EXPECT_NEAR(sim->engine().JointRate(0, 0), 10.0, 0.05);
  // Holding against a force beyond the limit: it gives way at (F - limit) / I.
  sim->engine().SetMotor(0, 0, 0.0, 1000.0);
  for (int n = 0; n < 10; ++n) ASSERT_TRUE(sim->Step());
  EXPECT_NEAR(sim->engine().JointRate(0, 0), 0.0, 0.01);
}

// A linear motor: a 2 kg block on a slider along x reaches its velocity,
// and its stop holds it at the end of its travel.
TEST_P(BothEngines, ALinearMotorDrivesASliderToItsStop) {
  const std::string world =
      "<world><gravity><x>0</x><y>0</y><z>0</z></gravity>"
      "<object type=\"Box\" name=\"Block\"><mass>2</mass>" + Vec("size", 0.2, 0.2, 0.2) +
      Transform(0, 1, 0) + "</object><joint type=\"Slider\" name=\"Rail\"><body1>Block</body1>"
      "<body2>world</body2>" + Vec("axis1", 1, 0, 0) + "</joint></world>";
  auto sim = MakeSim(world, {}, Params());
  sim->engine().SetStops(0, 0, -1.0, 0.3);
  sim->engine().SetMotor(0, 0, 0.5, 100.0);
  for (int n = 0; n < 100; ++n) ASSERT_TRUE(sim->Step());
  EXPECT_NEAR(sim->engine().JointRate(0, 0), 0.5, 0.005);
  EXPECT_NEAR(sim->engine().ReadBody(0).linear_velocity.x(), 0.5, 0.005);
  for (int n = 0; n < 1000; ++n) ASSERT_TRUE(sim->Step());
  EXPECT_NEAR(sim->engine().JointPosition(0, 0), 0.3, 0.005);
  EXPECT_NEAR(sim->engine().ReadBody(0).position.x(), 0.3, 0.005);
}

TEST_P(BothEngines, StopsHoldAHingeWithinItsRange) {
  auto sim = MakeSim(FreeWheelWorld(), {}, Params());
  sim->engine().SetStops(0, 0, -0.2, 0.3);
  for (int n = 0; n < 2000; ++n) {
    sim->engine().SetMotor(0, 0, 2.0, 0.05);
    ASSERT_TRUE(sim->Step());
  }
  EXPECT_NEAR(sim->engine().JointPosition(0, 0), 0.3, 0.01);
  for (int n = 0; n < 2000; ++n) {
    sim->engine().SetMotor(0, 0, -2.0, 0.05);
    ASSERT_TRUE(sim->Step());
  }
  EXPECT_NEAR(sim->engine().JointPosition(0, 0), -0.2, 0.01);
}

// The bounce of a material: a ball dropped on it comes back up to about
// bounce^2 of its height.
TEST_P(BothEngines, BounceReturnsTheBallToBounceSquaredOfItsHeight) {
  const std::string world =
      std::string("<world><surface material=\"elastic\"><a>0</a><b>1</b><c>0</c><d>0</d>"
                  "</surface><material name=\"elastic\"><mu>1</mu><bounce>0.8</bounce>"
                  "<bounceVelocity>0.1</bounceVelocity></material>") +
      "<object type=\"Sphere\" name=\"Ball\" material=\"elastic\"><mass>1</mass>"
      "<radius>0.1</radius>" +
      Transform(0, 1.1, 0) + "</object></world>";
  auto sim = MakeSim(world, {}, Params());
  bool fell = false;
  double highest = 0.0;
  for (int n = 0; n < 1500; ++n) {
    ASSERT_TRUE(sim->Step());
    const BodyReadout b = sim->engine().ReadBody(0);
    if (b.position.y() < 0.2) fell = true;
    if (fell) highest = std::max(highest, b.position.y() - 0.1);
  }
  EXPECT_NEAR(highest, 0.64 * 1.0, 0.05);
}

// A joint that closes a loop of bodies has no place in MuJoCo's tree: it
// is refused at its file and line, never left out.
TEST(MujocoEngine, ALoopOfBodiesIsRefusedWithItsLine) {
  const std::string world =
      "<world><object type=\"Body\" name=\"A\"><mass>1</mass>" + Transform(0, 1, 0) +
      "</object><object type=\"Body\" name=\"B\"><mass>1</mass>" + Transform(1, 1, 0) +
      "</object>\n<joint type=\"Ball\" name=\"AB\"><body1>A</body1><body2>B</body2>" +
      Vec("anchor", 0.5, 1, 0) + "</joint>\n<joint type=\"Ball\" name=\"AW\"><body1>A</body1>"
      "<body2>world</body2>" + Vec("anchor", 0, 2, 0) + "</joint>\n<joint type=\"Ball\" "
      "name=\"BW\"><body1>B</body1><body2>world</body2>" + Vec("anchor", 1, 2, 0) +
      "</joint></world>";
  const model::World loaded = testing::LoadInline(world);
  const model::FlatModel flat = model::Flatten(loaded);
  const std::vector<Diagnostic> limits = EngineLimits(flat, Mujoco());
  ASSERT_EQ(limits.size(), 1u);
  EXPECT_EQ(limits[0].file, "test_world.xml");
  EXPECT_EQ(limits[0].line, 2);  // the tree hangs A and B from the world first
  EXPECT_NE(limits[0].message.find("'AB' closes a loop"), std::string::npos) << limits[0].message;
  EXPECT_TRUE(EngineLimits(flat, Parameters()).empty());  // ODE runs it
  EXPECT_THROW(Simulation(loaded, Mujoco(), 1), EngineError);
}

TEST_P(BothEngines, ARayStopsAtAWallAndSkipsItsOwnBody) {
  const std::string world =
      std::string("<world>") +
      "<object type=\"Box\" name=\"Wall\" static=\"true\">" + Vec("size", 0.2, 4, 4) +
      Transform(5.1, 0, 0) + "</object><object type=\"Sphere\" name=\"Head\"><mass>1</mass>"
      "<radius>0.5</radius>" + Transform(0, 0, 0) + "</object></world>";
  Parameters params = Params();
  auto sim = MakeSim(world, {}, params);
  ASSERT_TRUE(sim->Step());
  const int head = sim->flat().FindBody("", "Head");
  EXPECT_NEAR(sim->engine().CastRay({0, 0, 0}, {1, 0, 0}, 20, head), 5.0, 1e-9);
  EXPECT_NEAR(sim->engine().CastRay({0, 0, 0}, {1, 0, 0}, 20, -1), 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(sim->engine().CastRay({0, 0, 0}, {-1, 0, 0}, 20, head), 20.0);
  EXPECT_DOUBLE_EQ(sim->engine().CastRay({0, 0, 0}, {1, 0, 0}, 3, head), 3.0);
}

// A heightfield where the files put it: a ray straight down meets it at
// the height of its samples (scale s + offset, at its position) at every
// grid node, and linearly in between along a row (both engines make
// triangles of each cell, whose edges run along the rows and columns).
TEST_P(BothEngines, ARayDownMeetsTheHeightfieldAtItsSamples) {
  constexpr int kRows = 5, kColumns = 7;
  constexpr double kWidth = 6, kDepth = 4, kScale = 0.1, kOffset = 0.2;
  const Eigen::Vector3d at(1.0, 0.3, -0.5);
  std::vector<double> samples;
  std::string text;
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      samples.push_back((r * 3 + c * 5) % 4 + 0.5 * r);
      text += std::to_string(samples.back()) + " ";
    }
  const std::string world =
      "<world><heightfield rows=\"5\" columns=\"7\"><width>6</width><depth>4</depth>"
      "<scale>0.1</scale><offset>0.2</offset>" + Vec("position", at.x(), at.y(), at.z()) +
      "<samples>" + text + "</samples></heightfield>"
      "<object type=\"Sphere\" name=\"Far\"><mass>1</mass><radius>0.1</radius>" +
      Transform(50, 5, 50) + "</object></world>";
  auto sim = MakeSim(world, {}, Params());
  ASSERT_TRUE(sim->Step());
  auto height = [&](int r, double c) {  // c may lie between columns
    const int c0 = std::min(static_cast<int>(c), kColumns - 2);
    const double f = c - c0;
    const double s = samples[static_cast<size_t>(r * kColumns + c0)] * (1 - f) +
                     samples[static_cast<size_t>(r * kColumns + c0 + 1)] * f;
    return at.y() + kScale * s + kOffset;
  };
  // Inside the field: a ray exactly on its border may miss it in either
  // engine.
  for (int r = 1; r < kRows - 1; ++r) {
    for (const double c : {0.5, 1.0, 2.5, 3.0, 4.25, 5.5}) {
      const double x = at.x() - kWidth / 2 + c * kWidth / (kColumns - 1);
      const double z = at.z() - kDepth / 2 + r * kDepth / (kRows - 1);
      const double hit = sim->engine().CastRay({x, 10, z}, {0, -1, 0}, 20, -1);
      EXPECT_NEAR(10 - hit, height(r, c), 1e-5) << "row " << r << ", column " << c;
    }
  }
}

// MuJoCo's fatal errors would exit the process: once an engine is built
// they throw an EngineError through MuJoCo's own C frames instead.
TEST(MujocoEngine, AFatalMujocoErrorIsAnEngineErrorNotAnExit) {
  auto sim = MakeSim(ParticleWorld(10, 0, 0), {}, Mujoco());
  try {
    mju_error("out of memory in a test");
    FAIL() << "mju_error returned";
  } catch (const EngineError& e) {
    EXPECT_EQ(e.engine_message(), "out of memory in a test");
  }
  EXPECT_TRUE(sim->Step());  // thrown outside a step: the world is untouched
}

// Two runs of the same inputs are identical to the bit.
TEST(MujocoEngine, RunsRepeatToTheBit) {
  auto run = [] {
    auto sim = testing::MakeArmSim(-9.81, Mujoco());
    const int axle = sim->flat().FindJoint("", "Axle");
    for (int n = 0; n < 2000; ++n) {
      sim->engine().SetMotor(axle, 0, n % 300 < 150 ? 3.0 : -3.0, 5.0);
      sim->Step();
    }
    state_t state;
    sim->FillState(&state);
    state.utime = 0;  // the wall clock, the one field that may differ
    std::vector<uint8_t> bytes(static_cast<size_t>(state.getEncodedSize()));
    state.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace simpartner::sim
