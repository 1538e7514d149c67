// Actuator control laws and the parsing of actuator commands. Pure logic,
// no physics engine: the simulation feeds joint positions and rates in and
// applies the motor outputs (velocity target and force limit per axis) to
// the engine's joint motors (PhysicsEngine::SetMotor), so these rules are
// tested on their own.
#pragma once

#include <string>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/model/flat_model.h"

namespace simpartner::sim {

inline constexpr double kDefaultHoldForce = 1000.0;   // SPEC 4: hold with 1000 per axis
inline constexpr double kHoldGain = 20.0;             // [1/s] drift correction while holding
inline constexpr double kMaxMotorVelocity = 1000.0;   // [rad/s] or [m/s], commands beyond are refused
inline constexpr double kMaxMotorForce = 1e7;         // [N] or [N m]
inline constexpr double kMaxPidVelocity = 20.0;       // [rad/s] PID output saturation
inline constexpr double kMaxSliderPosition = 1e3;    // [m] slider targets and stops
inline constexpr double kMaxGain = 1e6;              // P, I, D gains

enum class ControlMode { kHold, kVelocity, kAngle };

// What an actuator is told to do; axes are the joint's own (0..num_axes-1).
struct ActuatorSetting {
  ControlMode mode = ControlMode::kHold;
  double max_force[2] = {kDefaultHoldForce, kDefaultHoldForce};
  double velocity[2] = {0, 0};   // kVelocity
  double target[2] = {0, 0};     // kHold, kAngle: joint position to reach
  double p = 0, i = 0, d = 0;    // kAngle gains: output [rad/s] per rad, per rad s, per rad/s
};

struct MotorOutput {
  double velocity[2] = {0, 0};
  double max_force[2] = {0, 0};
};

// Control state of one actuator: its setting and the PID memory.
class ActuatorController {
 public:
  ActuatorController() = default;
  ActuatorController(int num_axes, bool rotational);

  const ActuatorSetting& setting() const { return setting_; }
  // Replaces the setting; the integrator restarts when the target changes.
  void Apply(const ActuatorSetting& setting);
  // Motor command for the coming step from the joint's current position and
  // rate. Anti-windup: the integrator is frozen while the output is clamped
  // or the motor could not reach the last commanded velocity (force limit),
  // unless the error would unwind it.
  MotorOutput Update(const double position[2], const double rate[2], double dt);
  double integral(int axis) const { return integral_[axis]; }

 private:
  int num_axes_ = 1;
  bool rotational_ = true;
  ActuatorSetting setting_;
  double integral_[2] = {0, 0};
  double last_command_[2] = {0, 0};
  bool has_last_command_ = false;
};

// A parsed command for an actuator; error is empty when it is valid.
struct ParsedCommand {
  ActuatorSetting setting;
  bool sets_stops = false;
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  std::string error;
};

// Values of a command: the numeric array, or when empty the original
// comma-separated text ("1000,1000,100,0,0,0.2"). Errors name the field.
bool CommandValues(const std::vector<double>& values, const std::string& text,
                   std::vector<double>* out, std::string* error);

// Validates and converts a command (action from command_t) for the actuator
// of kind `kind` driving `joint`. Values in the original's three-slot form
// (e.g. 6 for a velocity controller) or the short per-axis form are
// accepted. Every number is checked: finite, forces >= 0, velocities and
// angles and stops in range; a slot of the long form that the joint does
// not use (x and y of a wheel's axle in z) sets nothing but is held to the
// same range, and a message names the slot.
ParsedCommand ParseActuatorCommand(int action, const std::vector<double>& values,
                                   model::ActuatorKind kind, const model::FlatJoint& joint,
                                   const ActuatorSetting& current);

// The setting as the original's slot form, e.g. "1000,1000,100,0,0,0.2".
std::vector<double> SettingToSlotValues(const ActuatorSetting& setting, const model::FlatJoint& joint);
std::string FormatValues(const std::vector<double>& values);

}  // namespace simpartner::sim
