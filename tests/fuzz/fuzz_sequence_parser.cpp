// libFuzzer target: arbitrary bytes as a sequence file (either version),
// and what parses checked against a small model (one robot with a wheel
// motor, an angle controller, a scanner and an echo sensor).
#include <cstddef>
#include <cstdint>
#include <string>

#include "simpartner/actuator_t.hpp"
#include "simpartner/sensor_t.hpp"
#include "simpartner/sequencer/check.h"
#include "simpartner/sequencer/sequence.h"

namespace {

// The real limit (250,000 commands) takes seconds per input under the
// sanitizers; the limit's code path is the same at 5000.
constexpr size_t kMaxFuzzCommands = 5000;

simpartner::model_t SmallModel() {
  using namespace simpartner;
  model_t m{};
  m.step_size = 0.001;
  m.state_every = 1;
  m.robots.resize(1);
  m.robots[0].name = "Bot";
  for (const char* name : {"Axle", "Turner"}) {
    joint_t j{};
    j.name = name;
    j.robot = 0;
    j.kind = joint_t::KIND_HINGE;
    j.num_axes = 1;
    m.joints.push_back(j);
  }
  actuator_t wheel{};
  wheel.name = "AxleMotor";
  wheel.kind = actuator_t::KIND_JOINT_VELOCITY;
  wheel.joint = 0;
  wheel.port = 1028;
  wheel.num_axes = 1;
  actuator_t turner = wheel;
  turner.id = 1;
  turner.name = "TurnerMotor";
  turner.kind = actuator_t::KIND_ANGLE;
  turner.joint = 1;
  turner.port = 1032;
  m.actuators = {wheel, turner};
  sensor_t scanner{};
  scanner.name = "Scanner";
  scanner.kind = sensor_t::KIND_SCANNER;
  scanner.body = -1;
  scanner.joint = -1;
  scanner.port = 1027;
  scanner.params = {11, 0.1, 10};
  scanner.num_params = 3;
  sensor_t echo = scanner;
  echo.id = 1;
  echo.name = "Echo";
  echo.kind = sensor_t::KIND_ECHO;
  echo.port = 1025;
  echo.params.clear();
  echo.num_params = 0;
  m.sensors = {scanner, echo};
  m.num_robots = 1;
  m.num_joints = 2;
  m.num_actuators = 2;
  m.num_sensors = 2;
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const simpartner::model_t model = SmallModel();
  const std::string text(reinterpret_cast<const char*>(data), size);
  const simpartner::sequencer::SequenceParseResult parsed =
      simpartner::sequencer::ParseSequence(text, "fuzz.xml", kMaxFuzzCommands);
  if (!parsed.sequence && parsed.diagnostics.empty()) __builtin_trap();  // failure must say why
  if (parsed.sequence) {
    simpartner::sequencer::Plan plan;
    (void)simpartner::sequencer::CheckSequence(*parsed.sequence, model, &plan);
  }
  return 0;
}
