// The transport-free layer: names, ports and did-you-mean from a model_t;
// commands checked for their value counts before anything is sent.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "simpartner/actuator_t.hpp"
#include "simpartner/client/catalog.h"
#include "simpartner/client/command.h"
#include "simpartner/client/errors.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner::client {
namespace {

// Two robots, "Alpha" and "Beta", both with a wheel motor "Axle1Motor";
// only Alpha has TurnerMotor (angle) and a Scanner, only Beta a slider.
model_t TwoRobotModel() {
  model_t m{};
  m.simulation_id = 42;
  m.step_size = 0.002;
  m.state_every = 5;
  m.world_name = "Two";
  for (const char* name : {"Alpha", "Beta"}) {
    robot_t r{};
    r.name = name;
    r.model = std::string("model ") + name;
    m.robots.push_back(r);
  }
  auto joint = [&](const std::string& name, int robot, int axes) {
    joint_t j{};
    j.id = static_cast<int32_t>(m.joints.size());
    j.name = name;
    j.robot = static_cast<int16_t>(robot);
    j.num_axes = static_cast<int8_t>(axes);
    m.joints.push_back(j);
    return j.id;
  };
  auto body = [&](const std::string& name, int robot) {
    body_t b{};
    b.id = static_cast<int32_t>(m.bodies.size());
    b.name = name;
    b.robot = static_cast<int16_t>(robot);
    m.bodies.push_back(b);
  };
  auto actuator = [&](const std::string& name, int robot, int kind, int joint_index, int port,
                      int axes) {
    actuator_t a{};
    a.id = static_cast<int32_t>(m.actuators.size());
    a.name = name;
    a.robot = static_cast<int16_t>(robot);
    a.kind = static_cast<int8_t>(kind);
    a.joint = joint_index;
    a.port = port;
    a.num_axes = static_cast<int8_t>(axes);
    a.axis_slot[0] = 2;
    a.axis_slot[1] = 0;
    m.actuators.push_back(a);
  };
  body("Chassis", 0);
  body("Wheel1", 0);
  body("Chassis", 1);
  body("Ground", -1);
  const int a_axle = joint("Axle1", 0, 1);
  const int a_turner = joint("Turner", 0, 1);
  const int b_axle = joint("Axle1", 1, 1);
  const int b_slide = joint("Slide", 1, 1);
  const int b_ball = joint("Neck", 1, 2);
  actuator("Axle1Motor", 0, actuator_t::KIND_JOINT_VELOCITY, a_axle, 1028, 1);
  actuator("TurnerMotor", 0, actuator_t::KIND_ANGLE, a_turner, 1032, 1);
  actuator("Axle1Motor", 1, actuator_t::KIND_JOINT_VELOCITY, b_axle, 2028, 1);
  actuator("SlideMotor", 1, actuator_t::KIND_LINEAR_MOTOR, b_slide, 0, 1);
  actuator("NeckMotor", 1, actuator_t::KIND_ANGLE, b_ball, 0, 2);
  sensor_t s{};
  s.id = 0;
  s.name = "Scanner";
  s.robot = 0;
  s.kind = sensor_t::KIND_SCANNER;
  s.joint = -1;
  s.port = 1027;
  m.sensors.push_back(s);
  s.id = 1;
  s.name = "Echo";
  s.kind = sensor_t::KIND_ECHO;
  s.port = 1025;
  m.sensors.push_back(s);
  m.num_robots = static_cast<int16_t>(m.robots.size());
  m.num_bodies = static_cast<int32_t>(m.bodies.size());
  m.num_joints = static_cast<int32_t>(m.joints.size());
  m.num_actuators = static_cast<int32_t>(m.actuators.size());
  m.num_sensors = static_cast<int32_t>(m.sensors.size());
  return m;
}

TEST(Catalog, FindsByNameQualifiedNameAndPort) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  EXPECT_EQ(c.simulation_id(), 42);
  EXPECT_DOUBLE_EQ(c.step_size(), 0.002);
  EXPECT_EQ(c.state_every(), 5);
  ASSERT_EQ(c.robot_names().size(), 2u);
  const Target& turner = c.Find("TurnerMotor");
  EXPECT_EQ(turner.robot, "Alpha");
  EXPECT_EQ(turner.index, 1);
  EXPECT_EQ(turner.lcm_kind, actuator_t::KIND_ANGLE);
  EXPECT_EQ(turner.joint, "Turner");
  EXPECT_EQ(turner.port, 1032);
  EXPECT_EQ(c.Find("Beta/Axle1Motor").index, 2);
  EXPECT_EQ(c.Find("Alpha/Axle1Motor").index, 0);
  EXPECT_EQ(c.FindByPort(2028).qualified_name(), "Beta/Axle1Motor");
  EXPECT_EQ(c.Resolve("1027").name, "Scanner");
  EXPECT_TRUE(c.Resolve("Scanner").is_sensor());
  EXPECT_EQ(c.Find("Scanner").index, 0);
}

TEST(Catalog, AmbiguousNameListsBothRobots) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  try {
    c.Find("Axle1Motor");
    FAIL() << "an unqualified name in two robots must be refused";
  } catch (const UnknownTarget& e) {
    EXPECT_EQ(e.suggestions(), (std::vector<std::string>{"Alpha/Axle1Motor", "Beta/Axle1Motor"}));
    EXPECT_NE(std::string(e.what()).find("qualify it as robot/name"), std::string::npos) << e.what();
  }
  EXPECT_EQ(c.TryFind("Axle1Motor"), nullptr);
}

TEST(Catalog, UnknownNamesGetDidYouMean) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  try {
    c.Find("TurnerMoter");
    FAIL();
  } catch (const UnknownTarget& e) {
    ASSERT_FALSE(e.suggestions().empty());
    EXPECT_EQ(e.suggestions().front(), "TurnerMotor");
    EXPECT_EQ(e.name(), "TurnerMoter");
    EXPECT_NE(std::string(e.what()).find("did you mean 'TurnerMotor'"), std::string::npos)
        << e.what();
  }
  // Case slips count as near.
  EXPECT_EQ(c.Suggest("scanner").front(), "Scanner");
  // Nothing near: no suggestion rather than a random one.
  EXPECT_TRUE(c.Suggest("Gripper").empty());
  EXPECT_THROW(c.Find("Gamma/TurnerMotor"), UnknownTarget);
  EXPECT_THROW(c.FindByPort(1099), UnknownTarget);
  try {
    c.FindByPort(1029);
    FAIL();
  } catch (const UnknownTarget& e) {
    ASSERT_FALSE(e.suggestions().empty());
    EXPECT_EQ(e.suggestions().front(), "1028 (Axle1Motor)");
  }
}

TEST(Catalog, JointAndBodyIndices) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  EXPECT_EQ(c.JointIndex("Turner"), 1);
  EXPECT_EQ(c.JointIndex("Beta/Axle1"), 2);
  EXPECT_THROW(c.JointIndex("Axle1"), UnknownTarget);  // in both robots
  EXPECT_EQ(c.BodyIndex("Wheel1"), 1);
  EXPECT_EQ(c.BodyIndex("Ground"), 3);
  EXPECT_EQ(c.BodyIndex("Beta/Chassis"), 2);
  try {
    c.JointIndex("Turnr");
    FAIL();
  } catch (const UnknownTarget& e) {
    EXPECT_EQ(e.suggestions(), std::vector<std::string>{"Turner"});
  }
  EXPECT_EQ(c.StepAt(1.0), 500);
}

TEST(Catalog, ModelThatContradictsItselfIsAnError) {
  model_t m = TwoRobotModel();
  m.actuators[0].joint = 99;
  EXPECT_THROW(Catalog::FromModel(m), ClientError);
  m = TwoRobotModel();
  m.sensors[0].robot = 7;
  EXPECT_THROW(Catalog::FromModel(m), ClientError);
}

TEST(Catalog, DescribeNamesKindsPortsAndForms) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  const std::string text = c.Describe();
  EXPECT_NE(text.find("robot Alpha (model Alpha)"), std::string::npos) << text;
  EXPECT_NE(text.find("TurnerMotor  angle controller, port 1032, joint Turner"), std::string::npos)
      << text;
  EXPECT_NE(text.find("set: fmax_x,fmax_y,fmax_z,angle_x,angle_y,angle_z,P,I,D (9) or "
                      "fmax,angle,P,I,D (5)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("Scanner  scanner, port 1027"), std::string::npos) << text;
}

TEST(Command, ValueCountsFollowKindAndAction) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  const Target& axle = c.Find("Alpha/Axle1Motor");
  const Target& turner = c.Find("TurnerMotor");
  const Target& neck = c.Find("NeckMotor");
  const Target& slide = c.Find("SlideMotor");
  // SPEC 4: the original's three-slot form and the per-axis short form.
  EXPECT_NO_THROW(BuildCommandFromText(axle, command_t::ACTION_SET, "1000,1000,100,0,0,0.2"));
  EXPECT_NO_THROW(BuildCommandFromText(axle, command_t::ACTION_SET, "300, 1.0"));
  EXPECT_THROW(BuildCommandFromText(axle, command_t::ACTION_SET, "300,1,2"), BadValues);
  EXPECT_NO_THROW(BuildCommand(turner, command_t::ACTION_SET, {1000, 0.3, 100, 1, 0}));
  EXPECT_NO_THROW(BuildCommand(turner, command_t::ACTION_SET, std::vector<double>(9, 0.0)));
  EXPECT_THROW(BuildCommand(turner, command_t::ACTION_SET, {1000, 0.3}), BadValues);
  // Two axes: fmax1 fmax2 angle1 angle2 P I D.
  EXPECT_NO_THROW(BuildCommand(neck, command_t::ACTION_SET, std::vector<double>(7, 0.0)));
  EXPECT_THROW(BuildCommand(neck, command_t::ACTION_SET, std::vector<double>(5, 0.0)), BadValues);
  EXPECT_NO_THROW(BuildCommand(slide, command_t::ACTION_SET, {500, 0.1}));
  // Hold: no values, one force per slot or per axis.
  EXPECT_NO_THROW(BuildCommand(axle, command_t::ACTION_HOLD, {}));
  EXPECT_NO_THROW(BuildCommand(axle, command_t::ACTION_HOLD, {500}));
  EXPECT_NO_THROW(BuildCommand(axle, command_t::ACTION_HOLD, {0, 0, 500}));
  EXPECT_THROW(BuildCommand(axle, command_t::ACTION_HOLD, {1, 2}), BadValues);
  // Stops: lo, hi per slot or per axis.
  EXPECT_NO_THROW(BuildCommand(neck, command_t::ACTION_SET_STOPS, {-1, 1, -1, 1}));
  EXPECT_NO_THROW(BuildCommand(turner, command_t::ACTION_SET_STOPS, {0, 0, -1, 1, 0, 0}));
  EXPECT_THROW(BuildCommand(turner, command_t::ACTION_SET_STOPS, {-1, 1, 0}), BadValues);
  // Actions that do not apply.
  EXPECT_THROW(BuildCommand(axle, command_t::ACTION_READ, {}), BadValues);
  EXPECT_THROW(BuildCommand(axle, command_t::ACTION_SENSOR_PARAMS, {10}), BadValues);
}

TEST(Command, SensorsTakeParamsReadAndEcho) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  const Target& scanner = c.Find("Scanner");
  const Target& echo = c.Find("Echo");
  EXPECT_NO_THROW(BuildCommand(scanner, command_t::ACTION_SENSOR_PARAMS, {50}));
  EXPECT_NO_THROW(BuildCommand(scanner, command_t::ACTION_SENSOR_PARAMS, {50, 21, 0.5, 20}));
  EXPECT_THROW(BuildCommand(scanner, command_t::ACTION_SENSOR_PARAMS, {50, 21}), BadValues);
  EXPECT_THROW(BuildCommand(echo, command_t::ACTION_SENSOR_PARAMS, {50, 21, 0.5, 20}), BadValues);
  EXPECT_THROW(BuildCommand(scanner, command_t::ACTION_SET, {1}), BadValues);
  const command_t read = Read(scanner);
  EXPECT_EQ(read.action, command_t::ACTION_READ);
  EXPECT_EQ(read.num_values, 0);
  // An echo's SET text is text, not numbers.
  const command_t hello = BuildCommandFromText(echo, command_t::ACTION_SET, "hello, world");
  EXPECT_EQ(hello.text, "hello, world");
  EXPECT_TRUE(hello.values.empty());
}

TEST(Command, AddressedByRobotAndNameWithTheOriginalText) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  const command_t cmd =
      BuildCommandFromText(c.FindByPort(2028), command_t::ACTION_SET, " 1000,1000,100,0,0,0.2 ", 77);
  EXPECT_EQ(cmd.robot, "Beta");
  EXPECT_EQ(cmd.target, "Axle1Motor");
  EXPECT_EQ(cmd.port, 0);
  EXPECT_EQ(cmd.apply_at_step, 77);
  EXPECT_EQ(cmd.values, (std::vector<double>{1000, 1000, 100, 0, 0, 0.2}));
  EXPECT_EQ(cmd.num_values, 6);
  EXPECT_EQ(cmd.text, "1000,1000,100,0,0,0.2");
  const command_t v = SetVelocity(c.Find("SlideMotor"), {0.5}, 200);
  EXPECT_EQ(v.values, (std::vector<double>{200, 0.5}));
  const command_t a = SetAngle(c.Find("NeckMotor"), {0.1, 0.2}, 10, 1, 0.5, 300);
  EXPECT_EQ(a.values, (std::vector<double>{300, 300, 0.1, 0.2, 10, 1, 0.5}));
  // SetVelocity on an angle controller is the wrong shape (it needs gains).
  EXPECT_THROW(SetVelocity(c.Find("TurnerMotor"), {0.5}, 200), BadValues);
}

TEST(Command, BadNumbersNameTheItem) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  const Target& turner = c.Find("TurnerMotor");
  try {
    BuildCommandFromText(turner, command_t::ACTION_SET, "1000,abc,100,0,0");
    FAIL();
  } catch (const BadValues& e) {
    EXPECT_EQ(e.target(), "TurnerMotor");
    EXPECT_EQ(e.field(), "values[1]");
    EXPECT_EQ(e.value(), "abc");
  }
  EXPECT_THROW(BuildCommandFromText(turner, command_t::ACTION_SET, "1000,0.3,100,0,"), BadValues);
  EXPECT_THROW(BuildCommandFromText(turner, command_t::ACTION_SET, "1000,nan,100,0,0"), BadValues);
  const double inf = std::numeric_limits<double>::infinity();
  try {
    BuildCommand(turner, command_t::ACTION_SET, {1000, inf, 100, 0, 0});
    FAIL();
  } catch (const BadValues& e) {
    EXPECT_EQ(e.field(), "values[1] (angle)");
  }
  EXPECT_THROW(BuildCommand(turner, command_t::ACTION_SET, {1000, 0.3, 100, 0, 0}, -2), BadValues);
}

TEST(Command, RefusesWhatTheBusDoesNotCarrySafely) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  const Target& echo = c.Find("Echo");
  EXPECT_NO_THROW(BuildCommandFromText(echo, command_t::ACTION_SET, std::string(50000, 'x')));
  try {
    BuildCommandFromText(echo, command_t::ACTION_SET, std::string(70000, 'x'));
    FAIL();
  } catch (const BadValues& e) {
    EXPECT_NE(e.expected().find("at most 61440"), std::string::npos) << e.what();
  }
}

TEST(Command, StopWheelsZeroesEveryVelocityController) {
  const Catalog c = Catalog::FromModel(TwoRobotModel());
  const std::vector<command_t> stops = StopWheelsCommands(c, 800);
  ASSERT_EQ(stops.size(), 2u);  // Alpha's and Beta's Axle1Motor, not the angle or slider
  EXPECT_EQ(stops[0].robot, "Alpha");
  EXPECT_EQ(stops[1].robot, "Beta");
  for (const command_t& s : stops) EXPECT_EQ(s.values, (std::vector<double>{800, 0}));
}

}  // namespace
}  // namespace simpartner::client
