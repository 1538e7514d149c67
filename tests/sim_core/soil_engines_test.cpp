// A ground of soil (docs/soil.md) and the engines: both take a surface
// and a heightfield of soil, and one soil unit (soil_contact.h) answers
// the wheels on either, so the same wheel in the same state meets the
// same soil: the first step's soil figures agree on ODE and MuJoCo.
// A box on soil sinks on either as Bekker's plate.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "simpartner/sim/engine.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::LoadInline;

const std::string kSand =
    "<material name=\"sand\"><soil><n>1.1</n><kc>0.99</kc><kphi>1528.43</kphi>"
    "<cohesion>1.04</cohesion><frictionAngle>28</frictionAngle><shearModulus>0.025"
    "</shearModulus><unloadingStiffness>10000</unloadingStiffness><viscosity>0</viscosity>"
    "</soil></material>\n";

// A surface and a heightfield of the soil "sand".
const std::string kSoilWorld =
    "<world>\n<surface material=\"sand\"><a>0</a><b>1</b><c>0</c><d>0</d></surface>\n" + kSand +
    "<heightfield rows=\"2\" columns=\"2\" material=\"sand\"><width>4</width><depth>4</depth>"
    "<samples>0 0 0 0</samples></heightfield>\n</world>";

Parameters Engine(const std::string& name) {
  Parameters params;
  params.engine = name;
  return params;
}

TEST(SoilAndEngines, BothEnginesTakeASurfaceAndAHeightfieldOfSoil) {
  const model::World world = LoadInline(kSoilWorld);
  for (const char* engine : {"ode", "mujoco"}) {
    EXPECT_TRUE(EngineLimits(model::Flatten(world), Engine(engine)).empty()) << engine;
    EXPECT_NO_THROW(Simulation(world, Engine(engine), 1)) << engine;
  }
}

// A wheel 2 cm into the sand, moving at 1 m/s and spinning at 5 rad/s
// (its rim at 1.5 m/s: driving, slip 1/3): its first step's soil
// figures, per engine.
WheelSoilReadout FirstStep(const std::string& engine) {
  const std::string world_xml =
      "<world>" + testing::Vec("gravity", 0, -9.81, 0) +
      "<surface material=\"sand\"><a>0</a><b>1</b><c>0</c><d>0</d></surface>" + kSand +
      "<object type=\"Cylinder\" name=\"Wheel\"><mass>50</mass><radius>0.3</radius>"
      "<length>0.2</length>" + testing::Transform(0, 0.28, 0) +
      "<translationalVelocity><vx>1</vx><vy>0</vy><vz>0</vz></translationalVelocity>"
      "<rotationalVelocity><omegax>0</omegax><omegay>0</omegay><omegaz>-5</omegaz>"
      "</rotationalVelocity></object></world>";
  Simulation sim(LoadInline(world_xml), Engine(engine), 1);
  EXPECT_TRUE(sim.Step());
  const std::vector<WheelSoilReadout> wheels = sim.engine().ReadWheelSoil();
  EXPECT_EQ(wheels.size(), 1u) << engine;
  return wheels.empty() ? WheelSoilReadout{} : wheels[0];
}

TEST(SoilAndEngines, TheSameWheelMeetsTheSameSoilOnBothEngines) {
  const WheelSoilReadout ode = FirstStep("ode"), mujoco = FirstStep("mujoco");
  EXPECT_NEAR(ode.sinkage, 0.02, 1e-9);
  EXPECT_GT(ode.normal_force.y(), 0.0);
  EXPECT_GT(ode.shear_force.x(), 0.0);  // driving: the soil pushes it on
  EXPECT_NEAR(mujoco.sinkage, ode.sinkage, 1e-12);
  EXPECT_NEAR(mujoco.slip, ode.slip, 1e-12);
  // The forces are what the step applied: the same evaluation plus the
  // same rows, each engine solving them its own way (ODE with its other
  // constraints, MuJoCo's soil directly): equal to 1e-3.
  EXPECT_LT((mujoco.normal_force - ode.normal_force).norm(), 1e-3 * ode.normal_force.norm());
  EXPECT_LT((mujoco.shear_force - ode.shear_force).norm(), 1e-3 * ode.normal_force.norm());
  EXPECT_NEAR(mujoco.axle_torque, ode.axle_torque, 1e-3 * std::abs(ode.axle_torque));
}

// A 50 kg box (0.2 x 0.1 x 0.4 m) lowered onto the sand over 2 s sinks as
// Bekker's plate of its footprint, 0.2 m wide: p = W / A = (k_c / b +
// k_phi) z^n, so z = (W / (A (k_c / b + k_phi)))^(1 / n), on both engines.
TEST(SoilAndEngines, ABoxSinksAsBekkersPlateOnBothEngines) {
  std::string sand = kSand;
  sand.replace(sand.find("<viscosity>0"), 12, "<viscosity>60");  // about critical: no overshoot
  const std::string world_xml =
      "<world>" + testing::Vec("gravity", 0, -9.81, 0) +
      "<surface material=\"sand\"><a>0</a><b>1</b><c>0</c><d>0</d></surface>" + sand +
      "<object type=\"Box\" name=\"Crate\"><mass>50</mass>" + testing::Vec("size", 0.2, 0.1, 0.4) +
      testing::Transform(0, 0.05, 0) + "</object></world>";
  const double weight = 50 * 9.81, b = 0.2, area = 0.2 * 0.4;
  const double expected = std::pow(weight / (area * (0.99e3 / b + 1528.43e3)), 1 / 1.1);
  for (const char* engine : {"ode", "mujoco"}) {
    Simulation sim(LoadInline(world_xml), Engine(engine), 1);
    const int crate = sim.flat().FindBody("", "Crate");
    for (int k = 0; k < 3000; ++k) {
      const double support = k < 2000 ? weight * (1.0 - k / 2000.0) : 0.0;
      sim.engine().AddForce(crate, Eigen::Vector3d(0, support, 0));
      ASSERT_TRUE(sim.Step()) << engine << ", step " << k;
    }
    const BodyReadout box = sim.engine().ReadBody(crate);
    EXPECT_NEAR(0.05 - box.position.y(), expected, 0.01 * expected) << engine;
    EXPECT_LT(std::abs(box.position.x()) + std::abs(box.position.z()), 1e-6) << engine;
    EXPECT_NEAR(box.contact_force.y(), weight, 0.01 * weight) << engine;
  }
}

TEST(SoilAndEngines, AMaterialWithoutSoilIsNoneOfTheirConcern) {
  const model::World world = LoadInline(
      "<world><surface material=\"ice\"><a>0</a><b>1</b><c>0</c><d>0</d></surface>"
      "<material name=\"ice\"><mu>0.02</mu></material></world>");
  const model::FlatModel flat = model::Flatten(world);
  EXPECT_TRUE(EngineLimits(flat, Engine("mujoco")).empty());
  EXPECT_TRUE(EngineLimits(flat, Engine("ode")).empty());
}

}  // namespace
}  // namespace simpartner::sim
