// A wheel on soft soil inside ODE's step (issue 28): a 50 kg cylinder
// lowered slowly onto Wong's dry sand comes to rest at the sinkage where
// Bekker's pressure over its arc carries its weight, computed here apart
// from the sim (Simpson's rule and bisection), at 0.5, 1 and 2 ms steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

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

namespace simpartner::sim {
namespace {

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
};

// Lowered onto the sand over 1 s, then driven at slip i for 3 s; the last
// second's mean.
RigResult RunRig(const model::SoilParameters& soil, double slip, double omega,
                 double stepsize = 0.001) {
  model::World world = LoadInline(RigWorld());
  world.materials.at(0).soil = soil;
  Parameters params;
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
    ++counted;
  }
  out.sinkage /= counted;
  out.pull /= counted;
  return out;
}

// Issue 28 (c) and (d): drawbar pull and sinkage of the rig's wheel at
// slip 0.05 to 0.6 against Wong's rigid-wheel integrals for the same load
// (soil_closed_forms.h), and the same figures at 0.5 and 2 ms steps.
// The sim sums 64 points of the arc and remembers the ruts in 2 mm cells:
// within 0.5 % of the load for the pull, 0.5 % for the sinkage.
TEST(SoilContact, DrawbarPullAgainstSlipIsJanosiHanamotosIntegral) {
  model::SoilParameters soil = DrySand();
  soil.viscosity = 0;  // Wong's integrals have none
  constexpr double kLoad = 50 * kG;
  for (const double slip : {0.05, 0.1, 0.3, 0.6}) {
    const RigResult rig = RunRig(soil, slip, 1.0);
    const double z = testing::RollingSinkage(soil, kRadius, kWidth, slip, kLoad);
    const double pull = testing::RollingWheel(soil, kRadius, kWidth, z, slip).pull;
    // The rail holds the sled back: its force on the sled is minus the pull.
    EXPECT_NEAR(-rig.pull, pull, 0.005 * kLoad) << "slip " << slip;
    EXPECT_NEAR(rig.sinkage, z, 0.005 * z) << "slip " << slip;
    std::printf("slip %.2f: sinkage %.5f m (Wong %.5f), pull %.2f N (Wong %.2f)\n", slip,
                rig.sinkage, z, -rig.pull, pull);
  }
  const RigResult at_1ms = RunRig(soil, 0.3, 1.0, 0.001);
  for (const double h : {0.0005, 0.002}) {
    const RigResult rig = RunRig(soil, 0.3, 1.0, h);
    EXPECT_NEAR(rig.pull, at_1ms.pull, 0.005 * kLoad) << "step " << h;
    EXPECT_NEAR(rig.sinkage, at_1ms.sinkage, 0.005 * at_1ms.sinkage) << "step " << h;
    std::printf("step %.4f s, slip 0.3: sinkage %.5f m, pull %.2f N\n", h, rig.sinkage, -rig.pull);
  }
}

}  // namespace
}  // namespace simpartner::sim
