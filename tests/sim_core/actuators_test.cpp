// Actuators and sensors of the ArmBot (test_worlds.h): every expected number
// follows from its geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "simpartner/command_t.hpp"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::Command;
using testing::MakeArmSim;

int JointIndex(const Simulation& sim, const std::string& name) {
  const int j = sim.flat().FindJoint("", name);
  EXPECT_GE(j, 0) << name;
  return j;
}

void RunSteps(Simulation* sim, int steps) {
  for (int n = 0; n < steps; ++n) ASSERT_TRUE(sim->Step());
}

// Every actuator holds its initial position with 1000 per axis: the arm
// stays where it is, even when a side force pushes it.
TEST(Actuators, HoldInitialPositionByDefault) {
  auto sim = MakeArmSim();
  const int shoulder = JointIndex(*sim, "Shoulder");
  const int arm = sim->flat().FindBody("", "Arm");
  for (int n = 0; n < 2000; ++n) {
    sim->engine().AddForce(arm, Eigen::Vector3d(20, 0, 0));  // 10 N m about the hinge
    ASSERT_TRUE(sim->Step());
  }
  // Only the constraint softness (globalCFM) lets it give a little.
  EXPECT_NEAR(sim->engine().JointPosition(shoulder, 0), 0.0, 1e-4);
  const auto& setting = sim->controller(sim->flat().FindActuator("", "ArmMotor")).setting();
  EXPECT_EQ(setting.mode, ControlMode::kHold);
  EXPECT_EQ(setting.max_force[0], 1000.0);
}

TEST(Actuators, VelocityControllerReachesItsSpeed) {
  auto sim = MakeArmSim();
  // The original's three-slot form: the axle is along z, so slot 3.
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, 1000, 100, 0, 0, 2.0})));
  RunSteps(sim.get(), 500);
  const int axle = JointIndex(*sim, "Axle");
  EXPECT_NEAR(sim->engine().JointRate(axle, 0), 2.0, 1e-6);
  // The reply carries the previous setting (hold, 1000 on the axle's slot).
  const auto replies = sim->TakeReplies();
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_TRUE(replies[0].accepted);
  EXPECT_EQ(replies[0].applied_at_step, 0);
  EXPECT_EQ(replies[0].previous_text, "0,0,1000");
  // Short per-axis form: fmax, velocity.
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET, {100, -1.5})));
  RunSteps(sim.get(), 500);
  EXPECT_NEAR(sim->engine().JointRate(axle, 0), -1.5, 1e-6);
  EXPECT_EQ(sim->TakeReplies().at(0).previous_text, "0,0,100,0,0,2");
}

// The arm hangs at angle 0; the PID (output = joint velocity) takes it to
// 0.5 rad against gravity and holds it there. With P = 5/s the error decays
// as exp(-5 t): below 1e-8 rad after 4 s.
TEST(Actuators, AngleControllerReachesAndHolds) {
  auto sim = MakeArmSim();
  const int shoulder = JointIndex(*sim, "Shoulder");
  ASSERT_FALSE(sim->Submit(Command("ArmMotor", command_t::ACTION_SET,
                                   {1000, 1000, 100, 0, 0, 0.5, 5.0, 0.0, 0.0})));
  RunSteps(sim.get(), 4000);
  EXPECT_NEAR(sim->engine().JointPosition(shoulder, 0), 0.5, 1e-3);
  RunSteps(sim.get(), 2000);
  EXPECT_NEAR(sim->engine().JointPosition(shoulder, 0), 0.5, 1e-4);
}

// Saturation: 1 N m cannot lift the 1 kg arm (it needs 9.81 * 0.5 * sin(a)
// N m, 2.4 N m at 0.5 rad), so the arm stalls below the target for 3 s. With
// anti-windup the integrator does not grow meanwhile, so once the force is
// raised the arm reaches the target without a large overshoot. P = 5, I = 6
// is near critical damping for a velocity-output PI (s^2 + P s + I); a
// wound-up integral of ~0.9 rad s would add I * 0.9 = 5 rad/s and overshoot
// by tenths of a radian.
TEST(Actuators, AngleControllerDoesNotWindUpWhileSaturated) {
  auto sim = MakeArmSim();
  const int shoulder = JointIndex(*sim, "Shoulder");
  const int motor = sim->flat().FindActuator("", "ArmMotor");
  ASSERT_FALSE(sim->Submit(Command("ArmMotor", command_t::ACTION_SET,
                                   {1, 1, 1, 0, 0, 0.5, 5.0, 6.0, 0.0})));
  RunSteps(sim.get(), 3000);
  const double stalled = sim->engine().JointPosition(shoulder, 0);
  EXPECT_LT(stalled, 0.3);  // it could not get there
  // Without anti-windup the integral would be about (0.5 - stalled) * 3 s.
  EXPECT_LT(std::abs(sim->controller(motor).integral(0)), 0.05 * (0.5 - stalled) * 3.0);
  ASSERT_FALSE(sim->Submit(Command("ArmMotor", command_t::ACTION_SET,
                                   {100, 100, 100, 0, 0, 0.5, 5.0, 6.0, 0.0})));
  double peak = 0.0;
  for (int n = 0; n < 5000; ++n) {
    ASSERT_TRUE(sim->Step());
    peak = std::max(peak, sim->engine().JointPosition(shoulder, 0));
  }
  EXPECT_LT(peak, 0.5 + 0.05);
  EXPECT_NEAR(sim->engine().JointPosition(shoulder, 0), 0.5, 1e-3);
}

TEST(Actuators, StopsHold) {
  auto sim = MakeArmSim();
  const int axle = JointIndex(*sim, "Axle");
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET_STOPS, {-0.2, 0.3})));
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, 1.0})));
  RunSteps(sim.get(), 2000);  // 2 s at 1 rad/s would be 2 rad without the stop
  EXPECT_NEAR(sim->engine().JointPosition(axle, 0), 0.3, 0.01);
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, -1.0})));
  RunSteps(sim.get(), 2000);
  EXPECT_NEAR(sim->engine().JointPosition(axle, 0), -0.2, 0.01);
}

TEST(Actuators, CommandTakesEffectInTheStepItNames) {
  auto sim = MakeArmSim();
  const int axle = JointIndex(*sim, "Axle");
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, 3.0}, 100)));
  RunSteps(sim.get(), 100);
  EXPECT_NEAR(sim->engine().JointRate(axle, 0), 0.0, 1e-9);
  EXPECT_TRUE(sim->TakeReplies().empty());  // replied to when applied
  RunSteps(sim.get(), 1);
  EXPECT_NEAR(sim->engine().JointRate(axle, 0), 3.0, 1e-3);  // in one step, less CFM slip
  const auto replies = sim->TakeReplies();
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].applied_at_step, 100);
}

TEST(Actuators, OriginalCommandStringAndLegacyPort) {
  auto sim = MakeArmSim();
  command_t c{};
  c.port = 1028;
  c.text = "1000,1000,100,0,0,0.2";
  c.apply_at_step = -1;
  ASSERT_FALSE(sim->Submit(c));
  RunSteps(sim.get(), 300);
  EXPECT_NEAR(sim->engine().JointRate(JointIndex(*sim, "Axle"), 0), 0.2, 1e-6);
  EXPECT_EQ(sim->TakeReplies().at(0).target, "Spin");
}

TEST(Sensors, PositionSensorIsTheBodyPose) {
  auto sim = MakeArmSim();
  ASSERT_FALSE(sim->Submit(Command("ArmMotor", command_t::ACTION_SET,
                                   {1000, 1000, 100, 0, 0, 0.5, 5.0, 0.0, 0.0})));
  RunSteps(sim.get(), 3000);
  const int sensor = sim->flat().FindSensor("", "ArmPosition");
  const sensor_reading_t r = sim->ReadSensor(sensor);
  ASSERT_EQ(r.values.size(), 7u);
  // As in ODE, a joint's position is body1's rotation relative to body2:
  // the Shoulder at angle a has turned the Arm (body2) by -a about z. The
  // arm centre, 0.5 m below the hinge at (0.7, 2, 0), is then at
  // (0.7 - 0.5 sin a, 2 - 0.5 cos a, 0).
  const double a = sim->engine().JointPosition(JointIndex(*sim, "Shoulder"), 0);
  EXPECT_NEAR(a, 0.5, 1e-3);
  EXPECT_NEAR(r.values[0], 0.7 - 0.5 * std::sin(a), 1e-3);
  EXPECT_NEAR(r.values[1], 2.0 - 0.5 * std::cos(a), 1e-3);
  EXPECT_NEAR(r.values[2], 0.0, 1e-6);
  // Quaternion of a rotation a about z: (cos a/2, 0, 0, sin a/2).
  EXPECT_NEAR(std::abs(r.values[3]), std::cos(a / 2), 1e-3);
  EXPECT_NEAR(std::abs(r.values[6]), std::sin(a / 2), 1e-3);
}

TEST(Sensors, ForceTorqueSensorCarriesTheArmWeight) {
  auto sim = MakeArmSim();
  RunSteps(sim.get(), 1000);
  const sensor_reading_t r = sim->ReadSensor(sim->flat().FindSensor("", "ShoulderLoad"));
  ASSERT_EQ(r.values.size(), 6u);
  // The joint holds the hanging 1 kg arm up: +9.81 N along y on the arm.
  EXPECT_NEAR(r.values[1], 9.81, 1e-3);
  EXPECT_NEAR(r.values[0], 0.0, 1e-3);
}

TEST(Sensors, EchoReturnsTheLastCommand) {
  auto sim = MakeArmSim();
  command_t c = Command("Echo", command_t::ACTION_SET, {});
  c.text = "hello 1";
  ASSERT_FALSE(sim->Submit(c));
  RunSteps(sim.get(), 1);
  auto readings = sim->TakeSensorReadings();
  ASSERT_EQ(readings.size(), 1u);
  EXPECT_EQ(readings[0].text, "hello 1");
  c.text = "hello 2";
  ASSERT_FALSE(sim->Submit(c));
  RunSteps(sim.get(), 1);
  EXPECT_EQ(sim->TakeReplies().back().previous_text, "hello 1");
}

// A scanner 1 m above the ground looking along +x at a wall whose face is
// 4 m away: ray k at angle t_k reads 4 / cos(t_k).
TEST(Sensors, ScannerRangesMatchWallGeometry) {
  using testing::Transform;
  using testing::Vec;
  // Mount: rotate so that the sensor's z axis points along robot +x
  // (columns of R are the sensor axes in the body frame: x->-z, y->y, z->x).
  const std::string mount =
      "<transformation><T00>0</T00><T01>0</T01><T02>1</T02><T03>0.2</T03>"
      "<T10>0</T10><T11>1</T11><T12>0</T12><T13>0</T13>"
      "<T20>-1</T20><T21>0</T21><T22>0</T22><T23>0</T23></transformation>";
  const std::string robot =
      "<robot name=\"Eye\"><body type=\"Box\" name=\"Head\"><mass>10</mass>" +
      Vec("size", 0.4, 0.4, 0.4) + Transform(0, 1, 0) +
      "</body><sensor type=\"Scanner\" name=\"Scanner\"><bodyRef>Head</bodyRef>" + mount +
      "</sensor></robot>";
  const std::string world =
      "<world><gravity><x>0</x><y>0</y><z>0</z></gravity>"
      "<object type=\"Box\" name=\"Wall\" static=\"true\">" +
      Vec("size", 0.2, 3, 6) + Transform(4.3, 1, 0) +
      "</object><robot name=\"R\" file=\"eye.xml\"/></world>";
  auto sim = testing::MakeSim(world, {{"eye.xml", robot}});
  ASSERT_TRUE(sim->Step());
  const sensor_reading_t r = sim->ReadSensor(sim->flat().FindSensor("", "Scanner"));
  ASSERT_EQ(r.values.size(), 11u);
  for (int k = 0; k < 11; ++k) {
    const double angle = -0.1 + 0.02 * k;
    // The wall face is at x = 4.2; the scanner at x = 0.2.
    EXPECT_NEAR(r.values[k], 4.0 / std::cos(angle), 1e-6) << "ray " << k;
  }
  // Shrink the range below the wall: every ray reads the max range.
  command_t params = Command("Scanner", command_t::ACTION_SENSOR_PARAMS, {0, 11, 0.1, 3.0});
  ASSERT_FALSE(sim->Submit(params));
  ASSERT_TRUE(sim->Step());
  const sensor_reading_t short_range = sim->ReadSensor(sim->flat().FindSensor("", "Scanner"));
  for (double v : short_range.values) EXPECT_DOUBLE_EQ(v, 3.0);
  // At most 200,000 rays a second (model::kMaxScannerRaysPerSecond): the
  // issue's 10000 Hz x 10000 rays is refused; with 100 rays set, so is a
  // rate alone of 2001 Hz, and 2000 Hz is allowed.
  ASSERT_FALSE(sim->Submit(Command("Scanner", command_t::ACTION_SENSOR_PARAMS, {0, 100, 0.1, 3})));
  ASSERT_TRUE(sim->Step());
  for (const std::vector<double>& values :
       {std::vector<double>{10000, 10000, 3.14159, 10000}, std::vector<double>{2001}}) {
    const auto refused = sim->Submit(Command("Scanner", command_t::ACTION_SENSOR_PARAMS, values));
    ASSERT_TRUE(refused) << values[0];
    EXPECT_NE(refused->reason.find("rays/s is more than the 200000 rays/s a scanner may cast"),
              std::string::npos)
        << refused->reason;
  }
  EXPECT_FALSE(sim->Submit(Command("Scanner", command_t::ACTION_SENSOR_PARAMS, {2000})));
  EXPECT_FALSE(
      sim->Submit(Command("Scanner", command_t::ACTION_SENSOR_PARAMS, {20, 10000, 0.1, 3})));
}

// A robot's scanners together cast at most what one may (model::
// kMaxRobotRaysPerSecond). Each command alone is within the scanner's
// bound; the one that takes the robot over is refused when it applies,
// naming the robot, and changes nothing.
TEST(Sensors, ARobotsScannersTogetherStayWithinTheBusBudget) {
  using testing::Transform;
  using testing::Vec;
  std::string scanners;
  for (const char* name : {"Left", "Right"})
    scanners += std::string("<sensor type=\"Scanner\" name=\"") + name +
                "\"><bodyRef>Head</bodyRef></sensor>";
  const std::string robot = "<robot name=\"Eyes\"><body type=\"Box\" name=\"Head\">"
                            "<mass>10</mass>" + Vec("size", 0.4, 0.4, 0.4) +
                            Transform(0, 1, 0) + "</body>" + scanners + "</robot>";
  const std::string world =
      "<world><gravity><x>0</x><y>0</y><z>0</z></gravity>"
      "<robot name=\"R\" file=\"eyes.xml\"/></world>";
  auto sim = testing::MakeSim(world, {{"eyes.xml", robot}});
  // 11 rays each: Left at 10,000 Hz casts 110,000 rays/s.
  ASSERT_FALSE(sim->Submit(Command("Left", command_t::ACTION_SENSOR_PARAMS, {10000})));
  ASSERT_TRUE(sim->Step());
  ASSERT_TRUE(sim->TakeReplies().at(0).accepted);
  // Right at 9,000 Hz: 99,000 alone, 209,000 with Left.
  ASSERT_FALSE(sim->Submit(Command("Right", command_t::ACTION_SENSOR_PARAMS, {9000})));
  ASSERT_TRUE(sim->Step());
  const std::vector<command_reply_t> refused = sim->TakeReplies();
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_FALSE(refused[0].accepted);
  EXPECT_NE(refused[0].reason.find("robot 'R': its scanners and lidars together send 209000 "
                                   "rays/s (Left 110000, Right 99000), more than the 200000"),
            std::string::npos)
      << refused[0].reason;
  // Right kept its rate (on request): 8,000 Hz more fits, and it answers
  // with the rate it had.
  ASSERT_FALSE(sim->Submit(Command("Right", command_t::ACTION_SENSOR_PARAMS, {8000})));
  ASSERT_TRUE(sim->Step());
  const std::vector<command_reply_t> taken = sim->TakeReplies();
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_TRUE(taken[0].accepted) << taken[0].reason;
  EXPECT_EQ(taken[0].previous, (std::vector<double>{0, 11, 0.1, 10}));
}

}  // namespace
}  // namespace simpartner::sim
