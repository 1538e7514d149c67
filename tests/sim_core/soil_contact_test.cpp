// A wheel on soft soil inside each engine's step: a 50 kg cylinder
// lowered slowly onto Wong's dry sand comes to rest at the sinkage where
// Bekker's pressure over its arc carries its weight, computed here apart
// from the sim (Simpson's rule and bisection), at 0.5, 1 and 2 ms steps;
// driven on a single-wheel rig, its pull and sinkage are Wong's. Every
// test runs on ODE and on MuJoCo with the same tolerances.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../support/engines.h"
#include "soil_closed_forms.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::LoadInline;
using testing::Transform;

constexpr double kRadius = 0.3, kWidth = 0.2, kMass = 50.0, kG = 9.81;

model::SoilParameters DrySand() {
  model::SoilParameters p = testing::WongEntry(1.1, 0.99, 1528.43, 1.04, 28);  // dry sand (LLL)
  p.name = "dry_sand";
  // Damping about critical for this wheel (2 sqrt(k m) over the loaded
  // area): the lowering never overshoots, so the soil is loaded, never
  // unloaded. It does not enter the static sinkage.
  p.viscosity = 60;
  return p;
}

std::string WheelWorld() {
  return R"(<world name="Soil">)" + testing::Vec("gravity", 0, -kG, 0) +
         R"(<surface material="sand"><a>0</a><b>1</b><c>0</c><d>0</d></surface>
  <material name="sand"><mu>0.5</mu></material>
  <object type="Cylinder" name="Wheel"><mass>50</mass><radius>0.3</radius><length>0.2</length>)" +
         Transform(0, kRadius, 0) + R"(</object>
</world>)";
}

// The same wheel over a 4 x 4 m heightfield of sand (2 x 2 samples, row
// by row along z, x from -2 to 2) instead of the surface, at height y.
std::string HeightfieldWorld(const std::string& samples, double y) {
  return R"(<world name="Soil">)" + testing::Vec("gravity", 0, -kG, 0) +
         R"(<material name="sand"><mu>0.5</mu></material>
  <heightfield rows="2" columns="2" material="sand"><width>4</width><depth>4</depth><samples>)" +
         samples + R"(</samples></heightfield>
  <object type="Cylinder" name="Wheel"><mass>50</mass><radius>0.3</radius><length>0.2</length>)" +
         Transform(0, y, 0) + R"(</object>
</world>)";
}

std::unique_ptr<Simulation> MakeWheelOnSand(const std::string& engine, double stepsize,
                                            const std::string& world_xml = WheelWorld()) {
  model::World world = LoadInline(world_xml);
  world.materials.at(0).soil = DrySand();
  Parameters params;
  params.engine = engine;
  params.stepsize = stepsize;
  return std::make_unique<Simulation>(std::move(world), params, 1);
}

double BekkerSinkage() {
  double lo = 0.0, hi = kRadius / 2;
  for (int k = 0; k < 60; ++k) (testing::StandingLoad(DrySand(), kRadius, kWidth, 0.5 * (lo + hi)) < kMass * kG ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// Lowered over 2 s (a support force falling from m g to 0: the soil is
// loaded, never overshot and unloaded), then left 1 s; null on a failed step.
std::unique_ptr<Simulation> SettledWheel(const std::string& engine, double stepsize,
                                         const std::string& world_xml = WheelWorld()) {
  auto sim = MakeWheelOnSand(engine, stepsize, world_xml);
  const int wheel = sim->flat().FindBody("", "Wheel");
  const int ramp = static_cast<int>(std::lround(2.0 / stepsize));
  const int rest = static_cast<int>(std::lround(1.0 / stepsize));
  for (int k = 0; k < ramp + rest; ++k) {
    const double support = k < ramp ? kMass * kG * (1.0 - static_cast<double>(k) / ramp) : 0.0;
    sim->engine().AddForce(wheel, Eigen::Vector3d(0, support, 0));
    EXPECT_TRUE(sim->Step()) << "step " << k;
    if (::testing::Test::HasFailure()) return nullptr;
  }
  return sim;
}

double SettledSinkage(const std::string& engine, double stepsize, Eigen::Vector3d* drift) {
  auto sim = SettledWheel(engine, stepsize);
  if (!sim) return NAN;
  const BodyReadout b = sim->engine().ReadBody(sim->flat().FindBody("", "Wheel"));
  *drift = Eigen::Vector3d(b.position.x(), 0, b.position.z());
  return kRadius - b.position.y();
}

class SoilContact : public ::testing::TestWithParam<std::string> {};

TEST_P(SoilContact, AWheelRestsAtBekkersSinkageAtAnyStep) {
  const double expected = BekkerSinkage();
  EXPECT_GT(expected, 0.01);  // a few centimetres: the case Bekker's law is for
  for (const double h : {0.0005, 0.001, 0.002}) {
    Eigen::Vector3d drift = Eigen::Vector3d::Zero();
    const double sinkage = SettledSinkage(GetParam(), h, &drift);
    // The sim sums 64 points of the arc (0.3 % of the load at most, so
    // 0.2 % of the sinkage at n + 1/2 = 1.6).
    EXPECT_NEAR(sinkage, expected, 0.005 * expected) << "step " << h;
    EXPECT_LT(drift.norm(), 1e-6) << "step " << h;
  }
}

// A soil without shear (c = 0, phi = 0: a lunar soil of the validation's
// compaction check) holds a wheel at rest by nothing along the ground; the
// wheel still rests at Bekker's sinkage, on either engine, and its friction
// rows stay finite (MuJoCo's step faulted with a non-finite acceleration
// when a resting wheel's rows had a slope of 0).
TEST_P(SoilContact, AWheelRestsOnASoilWithoutShear) {
  model::World world = LoadInline(WheelWorld());
  world.materials.at(0).soil = DrySand();
  world.materials.at(0).soil->cohesion = 0.0;
  world.materials.at(0).soil->friction_angle = 0.0;
  Parameters params;
  params.engine = GetParam();
  Simulation sim(std::move(world), params, 1);
  const int wheel = sim.flat().FindBody("", "Wheel");
  for (int k = 0; k < 3000; ++k) {
    const double support = k < 2000 ? kMass * kG * (1.0 - k / 2000.0) : 0.0;
    sim.engine().AddForce(wheel, Eigen::Vector3d(0, support, 0));
    ASSERT_TRUE(sim.Step()) << "step " << k;
  }
  const double expected = BekkerSinkage();  // Bekker's law has no shear in it
  EXPECT_NEAR(kRadius - sim.engine().ReadBody(wheel).position.y(), expected, 0.005 * expected);
}

// A heightfield of soil is the same soil: on a level field 0.5 m up the
// wheel rests at Bekker's sinkage below it, without drifting.
TEST_P(SoilContact, AWheelRestsAtBekkersSinkageOnAHeightfieldOfSoil) {
  auto sim = SettledWheel(GetParam(), 0.001, HeightfieldWorld("0.5 0.5 0.5 0.5", 0.5 + kRadius));
  ASSERT_TRUE(sim);
  const BodyReadout b = sim->engine().ReadBody(sim->flat().FindBody("", "Wheel"));
  const double expected = BekkerSinkage();
  EXPECT_NEAR(0.5 + kRadius - b.position.y(), expected, 0.005 * expected);
  EXPECT_LT(Eigen::Vector3d(b.position.x(), 0, b.position.z()).norm(), 1e-6);
}

// On a sloping field the wheel meets the tangent plane under it: slope
// 0.1 along x, so the soil's normal is (-0.1, 1, 0) normalized.
TEST_P(SoilContact, OnASlopingHeightfieldTheSoilsNormalIsTheSlopes) {
  auto sim = MakeWheelOnSand(GetParam(), 0.001, HeightfieldWorld("-0.2 0.2 -0.2 0.2", kRadius - 0.005));
  ASSERT_TRUE(sim->Step());
  const std::vector<WheelSoilReadout> wheels = sim->engine().ReadWheelSoil();
  ASSERT_EQ(wheels.size(), 1u);
  const Eigen::Vector3d expected = Eigen::Vector3d(-0.1, 1, 0).normalized();
  EXPECT_LT((wheels[0].up - expected).norm(), 1e-9) << wheels[0].up.transpose();
  EXPECT_GT(wheels[0].sinkage, 0.0);
}

// SIM_STATE's wheel_soil of the resting wheel: its sinkage is Bekker's
// (as above), the soil carries its weight, and nothing drives it.
TEST_P(SoilContact, TheStateCarriesTheRestingWheelsSoilFigures) {
  auto sim = SettledWheel(GetParam(), 0.001);
  ASSERT_TRUE(sim);
  const std::vector<WheelSoilReadout> wheels = sim->engine().ReadWheelSoil();
  ASSERT_EQ(wheels.size(), 1u);
  EXPECT_EQ(wheels[0].ground, SoilGround::kPlane);
  state_t state;
  sim->FillState(&state);
  ASSERT_EQ(state.num_wheel_soil, 1);
  ASSERT_EQ(state.wheel_soil.size(), 1u);
  const wheel_soil_t& w = state.wheel_soil[0];
  EXPECT_EQ(w.body, sim->flat().FindBody("", "Wheel"));
  const double expected = BekkerSinkage();
  EXPECT_NEAR(w.sinkage, expected, 0.005 * expected);
  EXPECT_NEAR(w.load, kMass * kG, 0.005 * kMass * kG);
  EXPECT_NEAR(w.normal_force[1], kMass * kG, 0.005 * kMass * kG);
  EXPECT_NEAR(w.slip, 0.0, 1e-6);
  EXPECT_NEAR(w.thrust, 0.0, 1e-3 * kMass * kG);
  EXPECT_NEAR(w.drawbar_pull, 0.0, 1e-3 * kMass * kG);
  EXPECT_NEAR(w.axle_torque, 0.0, 1e-3 * kMass * kG * kRadius);
  EXPECT_FALSE(w.stuck);
  // Its rut: a row of 2 cm cells across its 0.2 m tread as deep as it
  // sank, none deeper. Its lowest point, at x = 0, sits on a cell edge, so
  // the row beside may hold as much (it pressed there while drifting by a
  // hair, 1e-6 m or less): one row or two, never more.
  const std::vector<soil_ruts_t> ruts = sim->ruts().Snapshot();
  ASSERT_EQ(ruts.size(), 1u);
  int as_deep = 0;
  for (float depth : ruts[0].depth) {
    EXPECT_LE(depth, 1.01 * w.sinkage);
    if (std::abs(depth - w.sinkage) < 0.01 * w.sinkage) ++as_deep;
  }
  EXPECT_GE(as_deep, 10);
  EXPECT_LE(as_deep, 22);
}

// On rigid ground the same wheel has no soil figures.
TEST_P(SoilContact, TheStateHasNoWheelSoilOnRigidGround) {
  Parameters params;
  params.engine = GetParam();
  Simulation sim(LoadInline(WheelWorld()), params, 1);
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(sim.Step());
  state_t state;
  sim.FillState(&state);
  EXPECT_GT(state.bodies[0].contact_force[1], 0.0);  // it stands on the ground
  EXPECT_EQ(state.num_wheel_soil, 0);
  EXPECT_TRUE(state.wheel_soil.empty());
}

// The single-wheel rig of terramechanics: a sled on a rail along x (its
// speed v held by the rail's motor), a carrier hung from it on a vertical
// slider (free: the wheel carries the carrier's and its own weight, W =
// 490.5 N), the wheel on an axle in the carrier spun at omega. The rail's
// motor force is the wheel's drawbar pull.
std::string RigWorld() {
  return R"(<world name="Rig">)" + testing::Vec("gravity", 0, -kG, 0) +
         R"(<surface material="sand"><a>0</a><b>1</b><c>0</c><d>0</d></surface>
  <material name="sand"><mu>0.5</mu></material>
  <object type="Box" name="Sled"><mass>5</mass>)" + testing::Vec("size", 0.2, 0.1, 0.2) +
         Transform(0, 1.5, 0) + R"(</object>
  <object type="Box" name="Carrier"><mass>40</mass>)" + testing::Vec("size", 0.05, 0.05, 0.05) +
         Transform(0, kRadius, 0) + R"(</object>
  <object type="Cylinder" name="Wheel"><mass>10</mass><radius>0.3</radius><length>0.2</length>)" +
         Transform(0, kRadius, 0) + R"(</object>
  <joint type="Slider" name="Rail"><body1>Sled</body1><body2>world</body2>)" +
         testing::Vec("axis1", 1, 0, 0) + R"(</joint>
  <joint type="Slider" name="Hanger"><body1>Carrier</body1><body2>Sled</body2>)" +
         testing::Vec("axis1", 0, 1, 0) + R"(</joint>
  <joint type="Hinge" name="Axle"><body1>Carrier</body1><body2>Wheel</body2>)" +
         testing::Vec("anchor", 0, kRadius, 0) + testing::Vec("axis1", 0, 0, 1) + R"(</joint>
</world>)";
}

struct RigResult {
  double sinkage = 0, pull = 0;
  // Means of SIM_STATE's wheel_soil over the same second.
  double state_slip = 0, state_sinkage = 0, state_pull = 0, state_thrust = 0;
  // 1 - v / (r omega) from the wheel body's own velocities.
  double body_slip = 0;
};

void AddWheelSoil(const Simulation& sim, RigResult* out) {
  state_t state;
  sim.FillState(&state);
  EXPECT_EQ(state.num_wheel_soil, 1);
  if (state.wheel_soil.size() != 1) return;
  out->state_slip += state.wheel_soil[0].slip;
  out->state_sinkage += state.wheel_soil[0].sinkage;
  out->state_pull += state.wheel_soil[0].drawbar_pull;
  out->state_thrust += state.wheel_soil[0].thrust;
  const body_state_t& wheel = state.bodies[static_cast<size_t>(state.wheel_soil[0].body)];
  // Rolling toward +x spins the wheel about -z.
  out->body_slip += 1.0 - wheel.linear_velocity[0] / (-wheel.angular_velocity[2] * kRadius);
}

// Lowered onto the sand over 1 s, then driven at slip i for 3 s; the last
// second's mean.
RigResult RunRig(const std::string& engine, const model::SoilParameters& soil, double slip,
                 double omega, double stepsize = 0.001, bool with_state = false) {
  model::World world = LoadInline(RigWorld());
  world.materials.at(0).soil = soil;
  Parameters params;
  params.engine = engine;
  params.stepsize = stepsize;
  Simulation sim(std::move(world), params, 1);
  const int second = static_cast<int>(std::lround(1.0 / stepsize));
  const int rail = sim.flat().FindJoint("", "Rail"), axle = sim.flat().FindJoint("", "Axle");
  const int carrier = sim.flat().FindBody("", "Carrier"), wheel = sim.flat().FindBody("", "Wheel");
  RigResult out;
  int counted = 0;
  for (int k = 0; k < 4 * second; ++k) {
    const double lowering = k < second ? 1.0 - static_cast<double>(k) / second : 0.0;
    sim.engine().AddForce(carrier, Eigen::Vector3d(0, 50 * kG * lowering, 0));
    const bool driving = k >= second;
    sim.engine().SetMotor(rail, 0, driving ? (1 - slip) * kRadius * omega : 0.0, 1e5);
    // robot.dtd: a positive rate of body2 (the wheel) about the axle rolls
    // toward +x.
    sim.engine().SetMotor(axle, 0, driving ? omega : 0.0, 1e5);
    EXPECT_TRUE(sim.Step()) << "step " << k;
    if (::testing::Test::HasFailure()) return out;
    if (k < 3 * second) continue;
    out.sinkage += kRadius - sim.engine().ReadBody(wheel).position.y();
    out.pull += sim.engine().ReadJoint(rail).force1.x();
    if (with_state) AddWheelSoil(sim, &out);
    ++counted;
  }
  for (double* mean : {&out.sinkage, &out.pull, &out.state_slip, &out.state_sinkage,
                       &out.state_pull, &out.state_thrust, &out.body_slip})
    *mean /= counted;
  return out;
}

// Drawbar pull and sinkage of the rig's wheel at
// slip 0.05 to 0.6 against Wong's rigid-wheel integrals for the same load
// (soil_closed_forms.h), and the same figures at 0.5 and 2 ms steps.
// The sim sums 64 points of the arc and remembers the ruts in 2 mm cells:
// within 0.5 % of the load for the pull, 0.5 % for the sinkage.
TEST_P(SoilContact, DrawbarPullAgainstSlipIsJanosiHanamotosIntegral) {
  model::SoilParameters soil = DrySand();
  soil.viscosity = 0;  // Wong's integrals have none
  constexpr double kLoad = 50 * kG;
  for (const double slip : {0.05, 0.1, 0.3, 0.6}) {
    const RigResult rig = RunRig(GetParam(), soil, slip, 1.0);
    const double z = testing::RollingSinkage(soil, kRadius, kWidth, slip, kLoad);
    const double pull = testing::RollingWheel(soil, kRadius, kWidth, z, slip).pull;
    // The rail holds the sled back: its force on the sled is minus the pull.
    EXPECT_NEAR(-rig.pull, pull, 0.005 * kLoad) << "slip " << slip;
    EXPECT_NEAR(rig.sinkage, z, 0.005 * z) << "slip " << slip;
    std::printf("%s, slip %.2f: sinkage %.5f m (Wong %.5f), pull %.2f N (Wong %.2f)\n", GetParam().c_str(), slip,
                rig.sinkage, z, -rig.pull, pull);
  }
  const RigResult at_1ms = RunRig(GetParam(), soil, 0.3, 1.0, 0.001);
  for (const double h : {0.0005, 0.002}) {
    const RigResult rig = RunRig(GetParam(), soil, 0.3, 1.0, h);
    EXPECT_NEAR(rig.pull, at_1ms.pull, 0.005 * kLoad) << "step " << h;
    EXPECT_NEAR(rig.sinkage, at_1ms.sinkage, 0.005 * at_1ms.sinkage) << "step " << h;
    std::printf("%s, step %.4f s, slip 0.3: sinkage %.5f m, pull %.2f N\n", GetParam().c_str(), h,
                rig.sinkage, -rig.pull);
  }
}

// SIM_STATE's wheel_soil of the rig's wheel driven at slip 0.3: its slip
// is the rig's, its sinkage and drawbar pull Wong's (the tolerances of the
// test above), and the pull is the thrust less the compaction resistance.
TEST_P(SoilContact, TheStateCarriesTheDrivenWheelsSlipAndPull) {
  model::SoilParameters soil = DrySand();
  soil.viscosity = 0;
  constexpr double kLoad = 50 * kG, kSlip = 0.3;
  const RigResult rig = RunRig(GetParam(), soil, kSlip, 1.0, 0.001, true);
  const double z = testing::RollingSinkage(soil, kRadius, kWidth, kSlip, kLoad);
  const double pull = testing::RollingWheel(soil, kRadius, kWidth, z, kSlip).pull;
  // The motors hold the rig near slip 0.3 (within their compliance); the
  // state's slip is the wheel's own.
  EXPECT_NEAR(rig.state_slip, rig.body_slip, 1e-4);
  EXPECT_NEAR(rig.state_slip, kSlip, 0.01);
  EXPECT_NEAR(rig.state_sinkage, z, 0.005 * z);
  EXPECT_NEAR(rig.state_pull, pull, 0.005 * kLoad);
  EXPECT_GT(rig.state_thrust, rig.state_pull);  // compaction resistance > 0
  std::printf("SIM_STATE at slip %.2f: slip %.4f (the body's %.4f), sinkage %.5f m (Wong %.5f), pull %.2f N (Wong "
              "%.2f), thrust %.2f N\n",
              kSlip, rig.state_slip, rig.body_slip, rig.state_sinkage, z, rig.state_pull, pull, rig.state_thrust);
}

INSTANTIATE_TEST_SUITE_P(Engines, SoilContact, test_support::AllEngines(),
                         test_support::EngineTestName);

}  // namespace
}  // namespace simpartner::sim
