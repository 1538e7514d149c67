// A wheel on soft soil inside ODE's step (issue 28): a 50 kg cylinder
// lowered slowly onto Wong's dry sand comes to rest at the sinkage where
// Bekker's pressure over its arc carries its weight, computed here apart
// from the sim (Simpson's rule and bisection), at 0.5, 1 and 2 ms steps.
#include <gtest/gtest.h>

#include <cmath>

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

std::unique_ptr<Simulation> MakeWheelOnSand(double stepsize) {
  model::World world = LoadInline(WheelWorld());
  world.materials.at(0).soil = DrySand();
  Parameters params;
  params.stepsize = stepsize;
  return std::make_unique<Simulation>(std::move(world), params, 1);
}

double BekkerSinkage() {
  double lo = 0.0, hi = kRadius / 2;
  for (int k = 0; k < 60; ++k) (testing::StandingLoad(DrySand(), kRadius, kWidth, 0.5 * (lo + hi)) < kMass * kG ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// Lowered over 2 s (a support force falling from m g to 0: the soil is
// loaded, never overshot and unloaded), then left 1 s.
double SettledSinkage(double stepsize, Eigen::Vector3d* drift) {
  auto sim = MakeWheelOnSand(stepsize);
  const int wheel = sim->flat().FindBody("", "Wheel");
  const int ramp = static_cast<int>(std::lround(2.0 / stepsize));
  const int rest = static_cast<int>(std::lround(1.0 / stepsize));
  for (int k = 0; k < ramp + rest; ++k) {
    const double support = k < ramp ? kMass * kG * (1.0 - static_cast<double>(k) / ramp) : 0.0;
    sim->engine().AddForce(wheel, Eigen::Vector3d(0, support, 0));
    EXPECT_TRUE(sim->Step()) << "step " << k;
    if (::testing::Test::HasFailure()) return NAN;
  }
  const BodyReadout b = sim->engine().ReadBody(wheel);
  *drift = Eigen::Vector3d(b.position.x(), 0, b.position.z());
  return kRadius - b.position.y();
}

TEST(SoilContact, AWheelRestsAtBekkersSinkageAtAnyStep) {
  const double expected = BekkerSinkage();
  EXPECT_GT(expected, 0.01);  // a few centimetres: the case Bekker's law is for
  for (const double h : {0.0005, 0.001, 0.002}) {
    Eigen::Vector3d drift = Eigen::Vector3d::Zero();
    const double sinkage = SettledSinkage(h, &drift);
    // The sim sums 64 points of the arc (0.3 % of the load at most, so
    // 0.2 % of the sinkage at n + 1/2 = 1.6).
    EXPECT_NEAR(sinkage, expected, 0.005 * expected) << "step " << h;
    EXPECT_LT(drift.norm(), 1e-6) << "step " << h;
  }
}

}  // namespace
}  // namespace simpartner::sim
