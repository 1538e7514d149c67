// The Velocity sensor against a motion known in closed form: the ArmBot's
// wheel (test_worlds.h) spun at a set rate on its axle, the 1000 kg base
// resting. A point at radius r on the wheel moves at Omega x (p - axle);
// the hub does not move. On both engines.
#include <gtest/gtest.h>

#include <string>

#include "simpartner/command_t.hpp"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::Command;
using testing::MakeSim;
using testing::Transform;

constexpr double kRadius = 0.2;  // [m] mount of "Rim" from the wheel's centre
constexpr double kRate = 2.0;    // [rad/s] the Axle's set velocity

// The ArmBot with a Velocity and a Position sensor at the wheel's rim and
// a Velocity sensor at its hub.
std::string RobotWithWheelSensors() {
  std::string robot = testing::ArmRobot();
  const std::string sensors =
      "  <sensor type=\"Velocity\" name=\"Rim\"><bodyRef>Wheel</bodyRef>" +
      Transform(kRadius, 0, 0) + "</sensor>\n" +
      "  <sensor type=\"Position\" name=\"RimPosition\"><bodyRef>Wheel</bodyRef>" +
      Transform(kRadius, 0, 0) + "</sensor>\n" +
      "  <sensor type=\"Velocity\" name=\"Hub\"><bodyRef>Wheel</bodyRef></sensor>\n";
  const std::string before = "  <actuator type=\"AngleController\"";
  robot.insert(robot.find(before), sensors);
  return robot;
}

class VelocitySensor : public ::testing::TestWithParam<std::string> {};

TEST_P(VelocitySensor, ReadsTheRimAndHubOfASpinningWheel) {
  Parameters params;
  params.engine = GetParam();
  auto sim = MakeSim(testing::ArmWorld(), {{"arm.xml", RobotWithWheelSensors()}}, params);
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET, {100, kRate})));
  for (int n = 0; n < 700; ++n) ASSERT_TRUE(sim->Step());
  auto read = [&](const char* name) {
    const sensor_reading_t r = sim->ReadSensor(sim->flat().FindSensor("", name));
    return std::vector<double>(r.values.begin(), r.values.end());
  };
  const std::vector<double> rim = read("Rim"), hub = read("Hub"), at = read("RimPosition");
  ASSERT_EQ(rim.size(), 6u);
  ASSERT_EQ(hub.size(), 6u);
  ASSERT_EQ(at.size(), 7u);
  // robot.dtd: a positive Axle velocity rolls the robot forward (+x) with
  // the axle along +z and y up, so the wheel (body2) turns about -z.
  const Eigen::Vector3d omega(0, 0, -kRate);
  for (const auto* reading : {&rim, &hub})
    for (int k = 0; k < 3; ++k) EXPECT_NEAR((*reading)[3 + k], omega[k], 1e-4) << k;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(hub[k], 0.0, 1e-4) << "hub " << k;
  // The rim point is where the Position sensor puts it, at kRadius from
  // the axle (where the joint is now: the base settles on its contacts by
  // about 0.1 mm) in the wheel's plane; its velocity is Omega x (p - axle).
  const Eigen::Vector3d axle =
      sim->engine().ReadJoint(sim->flat().FindJoint("", "Axle")).anchor;
  EXPECT_NEAR((axle - Eigen::Vector3d(0, 1, 0.6)).norm(), 0.0, 1e-3);
  const Eigen::Vector3d p(at[0], at[1], at[2]);
  EXPECT_NEAR((p - axle).norm(), kRadius, 1e-6);
  EXPECT_NEAR(p.z(), axle.z(), 1e-6);
  const Eigen::Vector3d expected = omega.cross(p - axle);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(rim[k], expected[k], 1e-4) << "rim " << k;
  EXPECT_NEAR(Eigen::Vector3d(rim[0], rim[1], rim[2]).norm(), kRate * kRadius, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Engines, VelocitySensor,
                         ::testing::Values(std::string("ode"), std::string("mujoco")),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace simpartner::sim
