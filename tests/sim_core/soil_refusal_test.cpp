// A ground of soil (docs/soil.md) and the engines: MuJoCo does not model
// soil and refuses it at --check, at the <soil>'s file and line; ODE
// models a surface and a heightfield of soil.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "simpartner/sim/engine.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::LoadInline;

// A surface and a heightfield of the soil "sand", written out on line 3.
const std::string kSoilWorld =
    "<world>\n<surface material=\"sand\"><a>0</a><b>1</b><c>0</c><d>0</d></surface>\n"
    "<material name=\"sand\"><soil><n>1.1</n><kc>0.99</kc><kphi>1528.43</kphi>"
    "<cohesion>1.04</cohesion><frictionAngle>28</frictionAngle><shearModulus>0.025"
    "</shearModulus><unloadingStiffness>10000</unloadingStiffness><viscosity>0</viscosity>"
    "</soil></material>\n"
    "<heightfield rows=\"2\" columns=\"2\" material=\"sand\"><width>4</width><depth>4</depth>"
    "<samples>0 0 0 0</samples></heightfield>\n</world>";

Parameters Engine(const char* name) {
  Parameters params;
  params.engine = name;
  return params;
}

void ExpectSoilRefused(const std::vector<Diagnostic>& limits, const std::string& why) {
  ASSERT_EQ(limits.size(), 2u);
  const char* grounds[] = {"surface material 'sand' is a soil", "heightfield material 'sand'"};
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(limits[k].file, "test_world.xml");
    EXPECT_EQ(limits[k].line, 3);
    EXPECT_NE(limits[k].message.find(grounds[k]), std::string::npos) << limits[k].message;
    EXPECT_NE(limits[k].message.find(why), std::string::npos) << limits[k].message;
  }
}

TEST(SoilAndEngines, MujocoRefusesSoilAtTheSoilsLine) {
  const model::World world = LoadInline(kSoilWorld);
  const model::FlatModel flat = model::Flatten(world);
  ExpectSoilRefused(EngineLimits(flat, Engine("mujoco")), "the MuJoCo engine does not model soil");
  EXPECT_THROW(Simulation(world, Engine("mujoco"), 1), EngineError);
}

TEST(SoilAndEngines, OdeTakesASurfaceAndAHeightfieldOfSoil) {
  const model::World world = LoadInline(kSoilWorld);
  EXPECT_TRUE(EngineLimits(model::Flatten(world), Engine("ode")).empty());
  EXPECT_NO_THROW(Simulation(world, Engine("ode"), 1));
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
