// Coulomb friction must not depend on the direction of travel: the ground
// is isotropic, so a cube sliding at any heading brakes at mu g.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::MakeSim;
using testing::Transform;

// A 1 m, 1 kg cube resting on a floor of mu 0.5, sliding at v0 along the
// heading (angle from +x towards +z).
std::string SlidingCubeWorld(double v0, double heading) {
  return "<world name=\"Slide\"><surface material=\"floor\"><a>0</a><b>1</b><c>0</c><d>0</d>"
         "</surface><material name=\"floor\"><mu>0.5</mu></material>"
         "<object type=\"Box\" name=\"Cube\" material=\"floor\"><mass>1</mass>"
         "<size><x>1</x><y>1</y><z>1</z></size>" +
         Transform(0, 0.5, 0) + "<translationalVelocity><vx>" +
         std::to_string(v0 * std::cos(heading)) + "</vx><vy>0</vy><vz>" +
         std::to_string(v0 * std::sin(heading)) + "</vz></translationalVelocity></object></world>";
}

TEST(Friction, SlidingDistanceIsTheSameAtEveryHeading) {
  constexpr double kV0 = 10.0, kMu = 0.5, kG = 9.81;
  const double expected = kV0 * kV0 / (2.0 * kMu * kG);  // 10.19 m
  for (const double degrees : {0.0, 30.0, 45.0, 60.0, 135.0}) {
    SCOPED_TRACE("heading " + std::to_string(degrees) + " deg");
    const double heading = degrees * M_PI / 180.0;
    auto sim = MakeSim(SlidingCubeWorld(kV0, heading));
    for (int n = 0; n < 2500; ++n) ASSERT_TRUE(sim->Step());  // stops at 2.04 s
    const Eigen::Vector3d p = sim->ode().ReadBody(0).position;
    const double distance = std::hypot(p.x(), p.z());
    EXPECT_NEAR(distance, expected, 0.01 * expected);
    // Straight on: friction acts against the slip only.
    EXPECT_NEAR(std::atan2(p.z(), p.x()), std::atan2(std::sin(heading), std::cos(heading)), 1e-3);
    EXPECT_LT(sim->ode().ReadBody(0).linear_velocity.norm(), 1e-6);
  }
}

}  // namespace
}  // namespace simpartner::sim
