// Physics against closed-form answers: free fall under ODE's semi-implicit
// Euler, constant horizontal velocity, time keeping.
#include <gtest/gtest.h>

#include <cmath>

#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::MakeSim;
using testing::Transform;

std::string ParticleWorld(double height, double vx, double vz, double g) {
  return "<world name=\"Fall\"><gravity><x>0</x><y>" + std::to_string(-g) +
         "</y><z>0</z></gravity>"
         "<object type=\"Body\" name=\"TestParticle\"><mass>1</mass>" +
         Transform(0, height, 0) + "<translationalVelocity><vx>" + std::to_string(vx) +
         "</vx><vy>0</vy><vz>" + std::to_string(vz) +
         "</vz></translationalVelocity></object></world>";
}

// ODE integrates v += g dt, then x += v dt, so after n steps the height is
// h0 - g dt^2 n (n + 1) / 2 = h0 - g t^2 / 2 - (g dt / 2) t: the error
// against the exact fall grows linearly with slope g dt / 2 (SPEC 8:
// 0.0049 m/s for dt = 1 ms).
TEST(FreeFall, MatchesSemiImplicitEulerAndExactSlope) {
  for (const double g : {9.81, 50.0}) {
    Parameters params;
    params.stepsize = 0.001;
    auto sim = MakeSim(ParticleWorld(500, 0, 0, g), {}, params);
    const double dt = params.stepsize;
    double max_closed_form_error = 0.0;
    for (int n = 1; n <= 5000; ++n) {
      ASSERT_TRUE(sim->Step());
      const double y = sim->engine().ReadBody(0).position.y();
      const double expected = 500.0 - g * dt * dt * n * (n + 1) / 2.0;
      max_closed_form_error = std::max(max_closed_form_error, std::abs(y - expected));
    }
    EXPECT_LT(max_closed_form_error, 1e-9);
    const double t = sim->time();
    const double exact = 500.0 - g * t * t / 2.0;
    const double slope = (exact - sim->engine().ReadBody(0).position.y()) / t;
    EXPECT_NEAR(slope, g * dt / 2.0, 1e-6 * g) << "g = " << g;
  }
}

TEST(FreeFall, HorizontalVelocityIsKeptExactly) {
  auto sim = MakeSim(ParticleWorld(500, 10, 10, 9.81));
  for (int n = 0; n < 3000; ++n) ASSERT_TRUE(sim->Step());
  const BodyReadout b = sim->engine().ReadBody(0);
  // x = vx t; doubles accumulate 3000 additions of 0.01.
  EXPECT_NEAR(b.position.x(), 10.0 * sim->time(), 1e-9);
  EXPECT_NEAR(b.position.z(), 10.0 * sim->time(), 1e-9);
  EXPECT_DOUBLE_EQ(b.linear_velocity.x(), 10.0);
  EXPECT_DOUBLE_EQ(b.linear_velocity.z(), 10.0);
}

TEST(TimeKeeping, SimTimeIsStepCountTimesStepSize) {
  Parameters params;
  params.stepsize = 0.003;
  auto sim = MakeSim(ParticleWorld(10, 0, 0, 9.81), {}, params);
  for (int n = 0; n < 1000; ++n) sim->Step();
  EXPECT_EQ(sim->step(), 1000);
  EXPECT_DOUBLE_EQ(sim->time(), 1000 * 0.003);
  state_t state;
  sim->FillState(&state);
  EXPECT_EQ(state.step, 1000);
  EXPECT_DOUBLE_EQ(state.sim_time, 3.0);
}

// A sphere resting on the plane: the contact force balances its weight.
TEST(Contacts, RestingSphereContactForceEqualsWeight) {
  const std::string world =
      "<world><surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>"
      "<object type=\"Sphere\" name=\"Ball\"><mass>2</mass><radius>0.5</radius>" +
      Transform(0, 0.5, 0) + "</object></world>";
  auto sim = MakeSim(world);
  for (int n = 0; n < 2000; ++n) ASSERT_TRUE(sim->Step());
  const BodyReadout b = sim->engine().ReadBody(0);
  EXPECT_NEAR(b.contact_force.y(), 2 * 9.81, 1e-3);
  EXPECT_NEAR(b.position.y(), 0.5, 2e-3);
}

// Whatever order the collision space pairs a body with the ground or a
// static object (ODE swaps a joint attached to (null, body)), each sphere's
// contact force carries its weight.
TEST(Contacts, ContactForceOnEveryBodyWhateverThePairOrder) {
  std::string world =
      "<world><surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>"
      "<collisionSpace type=\"hash\"/>";
  for (int k = 0; k < 4; ++k) {
    const double x = 3.0 * k;
    world += "<object type=\"Box\" name=\"Table" + std::to_string(k) +
             "\" static=\"true\"><size><x>1</x><y>1</y><z>1</z></size>" +
             Transform(x, 0.5, 5) + "</object>";
    world += "<object type=\"Sphere\" name=\"OnTable" + std::to_string(k) +
             "\"><mass>" + std::to_string(k + 1) + "</mass><radius>0.25</radius>" +
             Transform(x, 1.25, 5) + "</object>";
    world += "<object type=\"Sphere\" name=\"OnGround" + std::to_string(k) +
             "\"><mass>" + std::to_string(k + 1) + "</mass><radius>0.25</radius>" +
             Transform(x, 0.25, 0) + "</object>";
  }
  world += "</world>";
  auto sim = MakeSim(world);
  for (int n = 0; n < 2000; ++n) ASSERT_TRUE(sim->Step());
  for (int i = 0; i < static_cast<int>(sim->flat().bodies.size()); ++i) {
    if (sim->flat().bodies[i].source->is_static) continue;
    const double weight = sim->flat().bodies[i].source->mass * 9.81;
    EXPECT_NEAR(sim->engine().ReadBody(i).contact_force.y(), weight, 1e-3 * weight)
        << sim->flat().bodies[i].name;
  }
}

// A joint to "world" reporting the force on its body: mujoco_engine_test.cpp
// (JointToTheWorldReportsTheForceOnItsBody, on both engines).

// Rolling friction (beyond the original): a rolling sphere comes to rest.
TEST(Contacts, RollingFrictionStopsARollingSphere) {
  auto rolling_speed_after = [](double rolling) {
    Parameters params;
    params.rollingFriction = rolling;
    const std::string world =
        "<world><surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>"
        "<object type=\"Sphere\" name=\"Ball\"><mass>1</mass><radius>0.5</radius>" +
        Transform(0, 0.5, 0) +
        "<translationalVelocity><vx>1</vx><vy>0</vy><vz>0</vz></translationalVelocity>"
        "<rotationalVelocity><omegax>0</omegax><omegay>0</omegay><omegaz>-2</omegaz>"
        "</rotationalVelocity></object></world>";
    auto sim = MakeSim(world, {}, params);
    for (int n = 0; n < 10000; ++n) sim->Step();
    return sim->engine().ReadBody(0).linear_velocity.norm();
  };
  EXPECT_GT(rolling_speed_after(0.0), 0.9);   // the original's sphere never stopped
  EXPECT_LT(rolling_speed_after(0.05), 1e-3);
}

}  // namespace
}  // namespace simpartner::sim
