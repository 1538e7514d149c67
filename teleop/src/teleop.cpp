#include "simpartner/teleop/teleop.h"

#include <SDL2/SDL_gamecontroller.h>

#include <algorithm>
#include <cmath>

#include "simpartner/client/command.h"

namespace simpartner::teleop {

static_assert(kAxisCount == SDL_CONTROLLER_AXIS_MAX, "SDL's axis count changed");
static_assert(kButtonCount == SDL_CONTROLLER_BUTTON_MAX, "SDL's button count changed");

bool InputState::operator==(const InputState& other) const {
  if (connected != other.connected) return false;
  for (int a = 0; a < kAxisCount; ++a)
    if (axis[a] != other.axis[a]) return false;
  for (int b = 0; b < kButtonCount; ++b)
    if (button[b] != other.button[b]) return false;
  return true;
}

double AxisFromSdl(int value) {
  return std::clamp(static_cast<double>(value) / 32767.0, -1.0, 1.0);
}

std::string Describe(StopReason reason) {
  switch (reason) {
    case StopReason::kNone: return "moving";
    case StopReason::kSignal: return "stopping (signal)";
    case StopReason::kNoController: return "stopped: no controller";
    case StopReason::kSimSilent: return "stopped: sim not heard";
    case StopReason::kNoPlan: return "stopped: no model or mapping";
    case StopReason::kDeadman: return "stopped: dead-man released";
  }
  return "?";
}

bool Demand::operator==(const Demand& other) const {
  return stop == other.stop && wheel_speed == other.wheel_speed &&
         steer_angle == other.steer_angle && levels == other.levels;
}

Controller::Controller(Plan plan) : plan_(std::move(plan)), levels_(plan_.levels.size(), 0.0) {}

double Controller::Stick(int axis, const InputState& input) const {
  if (axis < 0 || axis >= kAxisCount) return 0;
  const double v = input.axis[axis];
  if (std::abs(v) < plan_.deadzone) return 0;
  // Rescaled so that the output starts at 0 past the dead zone and still
  // reaches 1 at full deflection.
  const double sign = v < 0 ? -1 : 1;
  return sign * std::min(1.0, (std::abs(v) - plan_.deadzone) / (1 - plan_.deadzone));
}

Demand Controller::Update(const InputState& input, StopReason safety) {
  auto pressed = [&](int button) {
    return button >= 0 && button < kButtonCount && input.button[button];
  };
  Demand demand;
  demand.stop = safety;
  if (demand.stop == StopReason::kNone && !input.connected) demand.stop = StopReason::kNoController;
  if (demand.stop == StopReason::kNone && !pressed(plan_.deadman_button))
    demand.stop = StopReason::kDeadman;
  if (demand.moving()) {
    // Level buttons count on the press (edge), only with the dead-man held.
    for (size_t k = 0; k < plan_.levels.size(); ++k) {
      const Plan::Level& level = plan_.levels[k];
      auto edge = [&](int b) {
        return pressed(b) && !(b >= 0 && b < kButtonCount && previous_.button[b]);
      };
      double v = levels_[k];
      if (edge(level.button_plus)) v += level.step;
      if (edge(level.button_minus)) v -= level.step;
      levels_[k] = std::clamp(v, level.min, level.max);
    }
    demand.wheel_speed = plan_.drive_scale * Stick(plan_.drive_axis, input);
    if (plan_.steer) demand.steer_angle = plan_.steer->scale * Stick(plan_.steer->axis, input);
  }
  demand.levels = levels_;
  previous_ = input;
  return demand;
}

std::vector<command_t> CommandsFor(const Plan& plan, const Demand& demand, bool with_levels,
                                   bool with_holds) {
  std::vector<command_t> commands;
  for (const Plan::Wheel& w : plan.wheels)
    commands.push_back(client::SetVelocity(
        w.target, {demand.moving() ? w.sign * demand.wheel_speed : 0.0}, w.max_force));
  if (demand.moving()) {
    if (plan.steer) {
      const Gains& g = plan.steer->gains;
      commands.push_back(
          client::SetAngle(plan.steer->target, {demand.steer_angle}, g.p, g.i, g.d, g.fmax));
    }
    if (with_levels) {
      for (size_t k = 0; k < plan.levels.size(); ++k) {
        const Plan::Level& level = plan.levels[k];
        const double value = k < demand.levels.size() ? demand.levels[k] : 0.0;
        for (const Plan::LevelJoint& j : level.joints)
          commands.push_back(client::SetAngle(j.target, {j.factor * value}, level.gains.p,
                                              level.gains.i, level.gains.d, level.gains.fmax));
      }
    }
  } else if (with_holds) {
    if (plan.steer) commands.push_back(client::Hold(plan.steer->target, plan.steer->gains.fmax));
    for (const Plan::Level& level : plan.levels)
      for (const Plan::LevelJoint& j : level.joints)
        commands.push_back(client::Hold(j.target, level.gains.fmax));
  }
  return commands;
}

Pacer::Batch Pacer::Due(const Demand& demand, double now) {
  Batch batch;
  // A change waits for the period to end as an unchanged demand does:
  // at most one batch per period whatever the input does.
  if (now - last_time_ < period_) return batch;
  batch.send = true;
  batch.changed = !last_ || *last_ != demand;
  batch.stop_changed = !last_ || last_->moving() != demand.moving();
  batch.levels_changed = !last_ || last_->levels != demand.levels;
  repeats_ = batch.stop_changed || batch.levels_changed ? 0 : repeats_ + 1;
  batch.full = repeats_ % 10 == 0;
  last_time_ = now;
  last_ = demand;
  return batch;
}

}  // namespace simpartner::teleop
