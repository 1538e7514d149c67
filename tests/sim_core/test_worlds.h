// Small worlds and robots written inline for the sim tests, so that each
// test states the geometry its expected numbers come from.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "simpartner/model/loader.h"
#include "simpartner/sim/simulation.h"

namespace simpartner::sim::testing {

inline std::string Transform(double x, double y, double z) {
  auto n = [](double v) { return std::to_string(v); };
  return "<transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>" + n(x) +
         "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>" + n(y) +
         "</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>" + n(z) + "</T23></transformation>";
}

inline std::string Vec(const char* tag, double x, double y, double z) {
  return std::string("<") + tag + "><x>" + std::to_string(x) + "</x><y>" + std::to_string(y) +
         "</y><z>" + std::to_string(z) + "</z></" + tag + ">";
}

// Loads world_xml with robot files served from memory; fails the test on
// any diagnostic.
inline model::World LoadInline(const std::string& world_xml,
                               const std::map<std::string, std::string>& robots = {}) {
  const model::FileReader reader = [robots](const std::string& path, std::string* out) {
    const auto it = robots.find(path);
    if (it == robots.end()) return false;
    *out = it->second;
    return true;
  };
  model::WorldLoadResult result = model::ParseWorld(world_xml, "test_world.xml", reader);
  EXPECT_TRUE(result.world.has_value()) << result.diagnostics.Format();
  if (!result.world) return model::World{};
  return std::move(*result.world);
}

inline std::unique_ptr<Simulation> MakeSim(const std::string& world_xml,
                                           const std::map<std::string, std::string>& robots = {},
                                           Parameters params = Parameters()) {
  return std::make_unique<Simulation>(LoadInline(world_xml, robots), params, 1);
}

// A 1000 kg base box (1 x 2 x 1 m) resting on the ground with a 1 kg, 1 m
// arm hinged at its top edge about z (the arm hangs along -y at angle 0,
// its centre 0.5 m below the hinge), and a wheel on an axle along z. Actuator
// "ArmMotor" (AngleController, port 1030) drives "Shoulder"; "Spin"
// (JointController, port 1028) drives a wheel about z.
inline std::string ArmRobot() {
  return R"(<robot name="ArmBot">
  <body type="Box" name="Base"><mass>1000</mass>)" +
         Vec("size", 1, 2, 1) + Transform(0, 1, 0) + R"(</body>
  <body type="Box" name="Arm"><mass>1</mass>)" +
         Vec("size", 0.1, 1, 0.1) + Transform(0.7, 1.5, 0) + R"(</body>
  <body type="Cylinder" name="Wheel"><mass>1</mass><radius>0.2</radius><length>0.1</length>)" +
         Transform(0, 1, 0.6) + R"(</body>
  <joint type="Hinge" name="Shoulder"><body1>Base</body1><body2>Arm</body2>)" +
         Vec("anchor", 0.7, 2.0, 0) + Vec("axis1", 0, 0, 1) + R"(</joint>
  <joint type="Hinge" name="Axle"><body1>Base</body1><body2>Wheel</body2>)" +
         Vec("anchor", 0, 1, 0.6) + Vec("axis1", 0, 0, 1) + R"(</joint>
  <sensor type="Position" name="ArmPosition" port="1026"><bodyRef>Arm</bodyRef></sensor>
  <sensor type="Echo" name="Echo" port="1025"><bodyRef>Base</bodyRef></sensor>
  <sensor type="ForceTorque" name="ShoulderLoad" port="1027"><jointRef>Shoulder</jointRef></sensor>
  <actuator type="AngleController" name="ArmMotor" port="1030"><jointRef>Shoulder</jointRef></actuator>
  <actuator type="JointController" name="Spin" port="1028"><jointRef>Axle</jointRef></actuator>
</robot>)";
}

inline std::string ArmWorld(double gravity = -9.81) {
  return R"(<world name="ArmWorld">)" + Vec("gravity", 0, gravity, 0) +
         R"(<surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>
  <robot name="Bot" file="arm.xml"/>
</world>)";
}

// The arm world as files for a real simpartner-sim: dir/world.xml and the
// robot it places, dir/arm.xml. Returns the world's path.
inline std::string WriteArmWorld(const std::filesystem::path& dir) {
  std::ofstream(dir / "arm.xml") << ArmRobot();
  std::ofstream(dir / "world.xml") << ArmWorld();
  return (dir / "world.xml").string();
}

inline std::unique_ptr<Simulation> MakeArmSim(double gravity = -9.81,
                                              Parameters params = Parameters()) {
  return MakeSim(ArmWorld(gravity), {{"arm.xml", ArmRobot()}}, params);
}

inline command_t Command(const std::string& target, int8_t action, std::vector<double> values,
                         int64_t apply_at_step = -1) {
  command_t c{};
  c.request_id = 1;
  c.sender = "test";
  c.target = target;
  c.action = action;
  c.apply_at_step = apply_at_step;
  c.values = std::move(values);
  c.num_values = static_cast<int32_t>(c.values.size());
  return c;
}

}  // namespace simpartner::sim::testing
