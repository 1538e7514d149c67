// libFuzzer target: arbitrary bytes as a robot file and as a world file
// whose robot references resolve to one small valid robot in memory (or,
// for a name ending in ".fifo", to a file the reader refuses). Invariants:
// a failure says why, and whatever loads is within the physical ranges
// (models/README.md), so the sim can run it.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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

bool InRange(double value, double lo, double hi) { return value >= lo && value <= hi; }

// Traps unless every moving body is within the loader's ranges.
void CheckRanges(const std::vector<simpartner::model::Body>& bodies) {
  namespace limits = simpartner::model::limits;
  for (const simpartner::model::Body& b : bodies) {
    if (b.pose.translation().cwiseAbs().maxCoeff() > limits::kMaxCoordinate) __builtin_trap();
    if (b.is_static) continue;
    if (!InRange(b.mass, limits::kMinMass, limits::kMaxMass)) __builtin_trap();
    if (b.linear_velocity.norm() > limits::kMaxLinearSpeed) __builtin_trap();
    if (b.angular_velocity.norm() > limits::kMaxAngularSpeed) __builtin_trap();
  }
}

// Traps unless every soil is within its ranges (docs/soil.md).
void CheckSoils(const std::vector<simpartner::model::Material>& materials) {
  for (const simpartner::model::Material& m : materials) {
    if (!m.soil) continue;
    const simpartner::model::SoilParameters& s = *m.soil;
    if (!(s.n > 0 && s.k_c >= 0 && s.k_phi >= 0 && s.k_c + s.k_phi > 0 && s.cohesion >= 0 &&
          s.friction_angle >= 0 && s.friction_angle < 90 && s.shear_modulus > 0 &&
          s.unloading_stiffness >= 0 && s.unloading_growth >= 0 && s.viscosity >= 0))
      __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const simpartner::model::RobotLoadResult robot = simpartner::model::ParseRobot(text, "fuzz.xml");
  if (!robot.robot && robot.diagnostics.empty()) __builtin_trap();  // failure must say why
  if (robot.robot) CheckRanges(robot.robot->bodies);
  const simpartner::model::FileReader reader = [](const std::string& path, std::string* out) {
    const std::string refused = ".fifo";
    if (path.size() >= refused.size() &&
        path.compare(path.size() - refused.size(), refused.size(), refused) == 0)
      throw simpartner::model::ModelFileError(
          "not a regular file (FIFO); model files must be regular files", false);
    *out = kRobot;
    return true;
  };
  const simpartner::model::WorldLoadResult world =
      simpartner::model::ParseWorld(text, "fuzz.xml", reader);
  if (!world.world && world.diagnostics.empty()) __builtin_trap();
  if (world.world) {
    CheckRanges(world.world->objects);
    CheckSoils(world.world->materials);
    (void)simpartner::model::DescribeWorld(*world.world);
  }
  return 0;
}
