// libFuzzer target: arbitrary bytes as a robot file and as a world file
// whose robot reference resolves to one small valid robot in memory.
#include <cstddef>
#include <cstdint>
#include <string>

#include "simpartner/model/loader.h"

namespace {

const char* kRobot = R"(<robot name="Tiny">
  <body type="Box" name="A"><mass>1</mass><size><x>1</x><y>1</y><z>1</z></size>
    <transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03><T10>0</T10><T11>1</T11>
    <T12>0</T12><T13>0.5</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation></body>
  <body type="Sphere" name="B"><mass>1</mass><radius>0.2</radius>
    <transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>1</T03><T10>0</T10><T11>1</T11>
    <T12>0</T12><T13>0.5</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation></body>
  <joint type="Hinge" name="J"><body1>A</body1><body2>B</body2>
    <anchor><x>0.5</x><y>0.5</y><z>0</z></anchor><axis1><x>0</x><y>0</y><z>1</z></axis1></joint>
  <actuator type="JointController" name="M" port="1028"><jointRef>J</jointRef></actuator>
</robot>)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const simpartner::model::RobotLoadResult robot = simpartner::model::ParseRobot(text, "fuzz.xml");
  if (!robot.robot && robot.diagnostics.empty()) __builtin_trap();  // failure must say why
  const simpartner::model::FileReader reader = [](const std::string&, std::string* out) {
    *out = kRobot;
    return true;
  };
  const simpartner::model::WorldLoadResult world =
      simpartner::model::ParseWorld(text, "fuzz.xml", reader);
  if (!world.world && world.diagnostics.empty()) __builtin_trap();
  if (world.world) (void)simpartner::model::DescribeWorld(*world.world);
  return 0;
}
