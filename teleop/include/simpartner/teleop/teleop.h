// Teleop's logic, free of SDL state and of the bus: the controller input
// as plain values, the safety rules that decide whether the robot may
// move, the commands for a demand, and the pacing that sends them when
// they change and repeats them at a low rate, never faster.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/command_t.hpp"
#include "simpartner/teleop/mapping.h"

namespace simpartner::teleop {

// SDL_CONTROLLER_AXIS_MAX and SDL_CONTROLLER_BUTTON_MAX of SDL 2.26
// (checked against SDL's header in input.cpp).
inline constexpr int kAxisCount = 6;
inline constexpr int kButtonCount = 21;

// One sample of a game controller (or the keyboard standing in for one).
struct InputState {
  bool connected = false;
  double axis[kAxisCount] = {};  // -1..1 (triggers 0..1)
  bool button[kButtonCount] = {};
  bool operator==(const InputState& other) const;
  bool operator!=(const InputState& other) const { return !(*this == other); }
};
// SDL's axis value (-32768..32767) as -1..1.
double AxisFromSdl(int value);

// Why the robot is not allowed to move, most serious first.
enum class StopReason {
  kNone,
  kSignal,        // teleop is being stopped (SIGINT/SIGTERM)
  kNoController,  // no controller, or it was unplugged
  kSimSilent,     // nothing heard from the sim for too long
  kNoPlan,        // no model or no usable mapping yet
  kDeadman,       // the dead-man button is not held
};
std::string Describe(StopReason reason);

// What teleop asks of the robot.
struct Demand {
  StopReason stop = StopReason::kNoPlan;
  double wheel_speed = 0;          // [rad/s] forward (before each wheel's sign)
  double steer_angle = 0;          // [rad]
  std::vector<double> levels;      // per plan level
  bool moving() const { return stop == StopReason::kNone; }
  bool operator==(const Demand& other) const;
  bool operator!=(const Demand& other) const { return !(*this == other); }
};

// The silence after which the sim counts as gone: 0.5 s while it runs
// (SIM_STATE comes every few ms); while it is paused only SIM_STATUS comes,
// once a second, so then 1.5 s.
inline constexpr double kSilenceRunning = 0.5;
inline constexpr double kSilencePaused = 1.5;

// Turns input into demands with the plan's mapping. The level values
// (body height, torso, claws) are its state: a press of a level's button
// while the dead-man is held moves the value one step within its range.
class Controller {
 public:
  explicit Controller(Plan plan);
  const Plan& plan() const { return plan_; }
  // `safety`: a stop decided outside (signal, sim silent), kNone if none.
  Demand Update(const InputState& input, StopReason safety);
  const std::vector<double>& levels() const { return levels_; }

 private:
  double Stick(int axis, const InputState& input) const;
  Plan plan_;
  std::vector<double> levels_;
  InputState previous_;
};

// The commands for a demand. Moving: each wheel at sign * speed, the steer
// angle and (when `with_levels`) every level joint's angle. Stopped: zero
// velocity on every wheel and (when `with_holds`) ACTION_HOLD on the steer
// and level joints, so the robot keeps its pose.
std::vector<command_t> CommandsFor(const Plan& plan, const Demand& demand, bool with_levels,
                                   bool with_holds);

// When to send. A batch goes out at once when the demand changed and the
// last one is at least `period` old, else as soon as it is; an unchanged
// demand is repeated every `period`. Never two batches within `period`.
class Pacer {
 public:
  explicit Pacer(double period = 0.1) : period_(period) {}
  struct Batch {
    bool send = false;
    bool changed = false;       // the demand differs from the last batch's
    bool stop_changed = false;  // moving/stopped differs (first hold, first levels)
    bool levels_changed = false;
    // Every tenth repeat carries the joint angles again (a lost datagram
    // is mended within a second); the others only the wheels and steer.
    bool full = false;
  };
  Batch Due(const Demand& demand, double now);
  // Forget the last batch (new model): the next demand counts as changed.
  void Forget() { last_.reset(); }
  double period() const { return period_; }

 private:
  double period_;
  std::optional<Demand> last_;
  double last_time_ = -1e300;
  int repeats_ = 0;
};

}  // namespace simpartner::teleop
