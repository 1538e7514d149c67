// gen3 on the shipped snow (snow_field.xml), on both engines. At rest its
// wheels sink less than its calves clear the ground (214 mm); driven at
// 1.5 rad/s they dig in until the calves press the snow as plates
// (soil_plate.h), and it bogs down to a creep. What each wheel's slip and
// `stuck` then say is printed, for docs/soil.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "../support/engines.h"
#include "simpartner/model/loader.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

// How deep the lowest corner of box `body` is below y = 0 [m].
double BoxSinkage(Simulation& sim, int body) {
  const BodyReadout b = sim.engine().ReadBody(body);
  const Eigen::Vector3d half = sim.flat().bodies[static_cast<size_t>(body)].source->geometry.size / 2;
  double deepest = -1e9;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d local((corner & 1 ? 1 : -1) * half.x(), (corner & 2 ? 1 : -1) * half.y(),
                                (corner & 4 ? 1 : -1) * half.z());
    deepest = std::max(deepest, -(b.position + b.orientation * local).y());
  }
  return deepest;
}

double DeepestCalf(Simulation& sim) {
  double deepest = -1e9;
  for (int k = 1; k <= 4; ++k)
    deepest = std::max(deepest, BoxSinkage(sim, sim.flat().FindBody("WorkPartner", "Calf" + std::to_string(k))));
  return deepest;
}

class SoilSnow : public ::testing::TestWithParam<std::string> {};

TEST_P(SoilSnow, Gen3DrivenDigsInToItsCalvesAndBogsDown) {
  Parameters params;
  params.engine = GetParam();
  Simulation sim(
      model::LoadWorldOrThrow(std::string(SP_SOURCE_DIR) + "/models/worlds/snow_field.xml"),
      params, 1);
  // At rest the wheels sink, but less than the calves clear (214 mm).
  EXPECT_LT(DeepestCalf(sim), 0.0) << "the calves clear the snow at rest";
  for (int k = 1; k <= 4; ++k)
    ASSERT_FALSE(sim.Submit(testing::Command("Axle" + std::to_string(k) + "Motor",
                                             command_t::ACTION_SET, {1000, 1.5})));
  const int torso = sim.flat().FindBody("WorkPartner", "Torso");
  const double x0 = sim.engine().ReadBody(torso).position.x();
  double x_before_last_second = 0.0;
  for (int k = 1; k <= 3500; ++k) {
    ASSERT_TRUE(sim.Step()) << "step " << k;
    if (k == 2500) x_before_last_second = sim.engine().ReadBody(torso).position.x();
  }
  const double x = sim.engine().ReadBody(torso).position.x();
  const double calf = DeepestCalf(sim);
  std::printf("%s: moved %.3f m in 3.5 s, %.3f m in the last second (the rims turn 0.352 m/s); "
              "deepest calf %.1f mm in the snow\n",
              GetParam().c_str(), x - x0, x - x_before_last_second, 1e3 * calf);
  for (const WheelSoilReadout& w : sim.engine().ReadWheelSoil())
    std::printf("  %s: slip %.3f, sinkage %.1f mm, stuck %d\n",
                sim.flat().bodies[static_cast<size_t>(w.body)].name.c_str(), w.slip,
                1e3 * w.sinkage, w.stuck ? 1 : 0);
  EXPECT_GT(calf, 0.003) << "the calves press the snow";
  EXPECT_LT(std::abs(x - x_before_last_second), 0.1) << "it bogs down";
  EXPECT_LT(x - x0, 1.0);  // rolling freely it would go 1.2 m
}

INSTANTIATE_TEST_SUITE_P(Engines, SoilSnow, test_support::AllEngines(),
                         test_support::EngineTestName);

}  // namespace
}  // namespace simpartner::sim
