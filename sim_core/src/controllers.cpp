#include "simpartner/sim/controllers.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "simpartner/command_t.hpp"

namespace simpartner::sim {
namespace {

double WrapAngle(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a < 0) a += 2.0 * M_PI;
  return a - M_PI;
}

std::string Num(double v) {
  std::ostringstream out;
  out.precision(10);
  out << v;
  return out.str();
}

bool IsRotational(model::JointKind kind) { return kind != model::JointKind::kSlider; }

}  // namespace

ActuatorController::ActuatorController(int num_axes, bool rotational)
    : num_axes_(num_axes), rotational_(rotational) {}

void ActuatorController::Apply(const ActuatorSetting& setting) {
  const bool same_target = setting.mode == setting_.mode &&
                           setting.target[0] == setting_.target[0] &&
                           setting.target[1] == setting_.target[1];
  if (!same_target) integral_[0] = integral_[1] = 0.0;
  setting_ = setting;
}

MotorOutput ActuatorController::Update(const double position[2], const double rate[2],
                                       double dt) {
  MotorOutput out;
  for (int a = 0; a < num_axes_; ++a) {
    out.max_force[a] = setting_.max_force[a];
    double command = 0.0;
    switch (setting_.mode) {
      case ControlMode::kVelocity:
        command = setting_.velocity[a];
        break;
      case ControlMode::kHold: {
        double error = setting_.target[a] - position[a];
        if (rotational_) error = WrapAngle(error);
        command = std::clamp(kHoldGain * error, -kMaxPidVelocity, kMaxPidVelocity);
        break;
      }
      case ControlMode::kAngle: {
        double error = setting_.target[a] - position[a];
        if (rotational_) error = WrapAngle(error);
        // Derivative on the measurement: no kick when the target jumps.
        const double unclamped =
            setting_.p * error + setting_.i * integral_[a] - setting_.d * rate[a];
        command = std::clamp(unclamped, -kMaxPidVelocity, kMaxPidVelocity);
        const bool clamped = command != unclamped;
        // The motor reached its force limit when the joint did not follow
        // the velocity commanded for the step just taken.
        const bool force_limited =
            has_last_command_ &&
            std::abs(rate[a] - last_command_[a]) > 1e-3 + 0.05 * std::abs(last_command_[a]);
        const bool unwinding = error * integral_[a] < 0.0;
        if (!(clamped || force_limited) || unwinding) integral_[a] += error * dt;
        break;
      }
    }
    out.velocity[a] = command;
    last_command_[a] = command;
  }
  has_last_command_ = true;
  return out;
}

bool CommandValues(const std::vector<double>& values, const std::string& text,
                   std::vector<double>* out, std::string* error) {
  out->clear();
  if (!values.empty()) {
    *out = values;
    return true;
  }
  if (text.empty()) return true;
  std::string item;
  std::istringstream in(text);
  int index = 0;
  while (std::getline(in, item, ',')) {
    const size_t b = item.find_first_not_of(" \t");
    const size_t e = item.find_last_not_of(" \t");
    const std::string trimmed = b == std::string::npos ? "" : item.substr(b, e - b + 1);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(trimmed.c_str(), &end);
    if (trimmed.empty() || *end != '\0') {
      *error = "text value " + std::to_string(index + 1) + " '" + trimmed + "' is not a number";
      return false;
    }
    out->push_back(v);
    ++index;
  }
  return true;
}

ParsedCommand ParseActuatorCommand(int action, const std::vector<double>& v,
                                   model::ActuatorKind kind, const FlatJoint& joint,
                                   const ActuatorSetting& current) {
  ParsedCommand parsed;
  parsed.setting = current;
  const int n = joint.num_axes;
  const bool rotational = IsRotational(joint.source->kind);
  std::string& error = parsed.error;

  for (size_t k = 0; k < v.size(); ++k) {
    if (!std::isfinite(v[k])) {
      error = "values[" + std::to_string(k) + "] = " + Num(v[k]) + " is not a finite number";
      return parsed;
    }
  }
  // Index of axis a's entry in a group of per-axis values: three slots in
  // the original's long form, the joint's own axes in the short form.
  auto at = [&](bool slot_form, int group, int a) {
    return static_cast<size_t>(group * (slot_form ? 3 : n) + (slot_form ? joint.slot[a] : a));
  };
  auto field = [](size_t index) { return "values[" + std::to_string(index) + "]"; };
  auto check_force = [&](size_t index) {
    if (v[index] < 0.0 || v[index] > kMaxMotorForce)
      error = field(index) + " (max force) = " + Num(v[index]) + " is out of range [0, " +
              Num(kMaxMotorForce) + "]";
    return error.empty();
  };
  auto check_position = [&](size_t index, const char* what, int a) {
    const double x = v[index];
    const double lo = joint.source->lo_stop[a], hi = joint.source->hi_stop[a];
    if (rotational && (x < -M_PI || x > M_PI)) {
      error = field(index) + " (" + what + ") = " + Num(x) + " rad is outside [-pi, pi]";
    } else if (x < lo || x > hi) {
      error = field(index) + " (" + what + ") = " + Num(x) + " is outside joint '" + joint.name +
              "' range [" + Num(lo) + ", " + Num(hi) + "]";
    } else if (!rotational && std::abs(x) > 1e3) {
      error = field(index) + " (" + what + ") = " + Num(x) + " m is out of range";
    }
    return error.empty();
  };
  auto expect_sizes = [&](size_t long_form, size_t short_form) -> int {
    if (v.size() == long_form) return 1;
    if (v.size() == short_form) return 0;
    error = "expected " + std::to_string(long_form) + " values (three slots x, y, z)";
    if (short_form != long_form) error += " or " + std::to_string(short_form) + " (per axis)";
    error += ", got " + std::to_string(v.size());
    return -1;
  };

  switch (action) {
    case command_t::ACTION_SET: {
      if (kind == model::ActuatorKind::kAngle) {
        const int slot_form = expect_sizes(9, static_cast<size_t>(2 * n + 3));
        if (slot_form < 0) return parsed;
        ActuatorSetting s;
        s.mode = ControlMode::kAngle;
        for (int a = 0; a < n; ++a) {
          if (!check_force(at(slot_form, 0, a))) return parsed;
          if (!check_position(at(slot_form, 1, a), "target angle", a)) return parsed;
          s.max_force[a] = v[at(slot_form, 0, a)];
          s.target[a] = v[at(slot_form, 1, a)];
        }
        const size_t g = v.size() - 3;
        const char* names[3] = {"P", "I", "D"};
        for (int k = 0; k < 3; ++k) {
          if (v[g + k] < 0.0 || v[g + k] > 1e6) {
            error = field(g + k) + " (" + names[k] + " gain) = " + Num(v[g + k]) +
                    " is out of range [0, 1e6]";
            return parsed;
          }
        }
        s.p = v[g];
        s.i = v[g + 1];
        s.d = v[g + 2];
        parsed.setting = s;
      } else {
        const int slot_form = expect_sizes(6, static_cast<size_t>(2 * n));
        if (slot_form < 0) return parsed;
        ActuatorSetting s;
        s.mode = ControlMode::kVelocity;
        for (int a = 0; a < n; ++a) {
          if (!check_force(at(slot_form, 0, a))) return parsed;
          const size_t vi = at(slot_form, 1, a);
          if (std::abs(v[vi]) > kMaxMotorVelocity) {
            error = field(vi) + " (velocity) = " + Num(v[vi]) + " is out of range [-" +
                    Num(kMaxMotorVelocity) + ", " + Num(kMaxMotorVelocity) + "]";
            return parsed;
          }
          s.max_force[a] = v[at(slot_form, 0, a)];
          s.velocity[a] = v[vi];
        }
        parsed.setting = s;
      }
      return parsed;
    }
    case command_t::ACTION_HOLD: {
      // Optional max forces; the target is the position when applied.
      ActuatorSetting s;
      s.mode = ControlMode::kHold;
      if (!v.empty()) {
        const int slot_form = expect_sizes(3, static_cast<size_t>(n));
        if (slot_form < 0) return parsed;
        for (int a = 0; a < n; ++a) {
          if (!check_force(at(slot_form, 0, a))) return parsed;
          s.max_force[a] = v[at(slot_form, 0, a)];
        }
      }
      parsed.setting = s;
      return parsed;
    }
    case command_t::ACTION_SET_STOPS: {
      const int slot_form = expect_sizes(6, static_cast<size_t>(2 * n));
      if (slot_form < 0) return parsed;
      // Long form: lo1 hi1 lo2 hi2 lo3 hi3 by slot; short: lo, hi per axis.
      for (int a = 0; a < n; ++a) {
        const size_t base = static_cast<size_t>(2 * (slot_form ? joint.slot[a] : a));
        if (!check_position(base, "low stop", a) || !check_position(base + 1, "high stop", a))
          return parsed;
        if (v[base] > v[base + 1]) {
          error = field(base) + " (low stop) = " + Num(v[base]) + " is above " + field(base + 1) +
                  " (high stop) = " + Num(v[base + 1]);
          return parsed;
        }
        parsed.lo[a] = v[base];
        parsed.hi[a] = v[base + 1];
      }
      parsed.sets_stops = true;
      return parsed;
    }
    default:
      error = "action " + std::to_string(action) + " does not apply to an actuator";
      return parsed;
  }
}

std::vector<double> SettingToSlotValues(const ActuatorSetting& s, const FlatJoint& joint) {
  std::vector<double> values;
  auto group = [&](const double* per_axis, double fill) {
    double slots[3] = {fill, fill, fill};
    for (int a = 0; a < joint.num_axes; ++a) slots[joint.slot[a]] = per_axis[a];
    for (double slot_value : slots) values.push_back(slot_value);
  };
  switch (s.mode) {
    case ControlMode::kHold:
      group(s.max_force, 0.0);
      break;
    case ControlMode::kVelocity:
      group(s.max_force, 0.0);
      group(s.velocity, 0.0);
      break;
    case ControlMode::kAngle:
      group(s.max_force, 0.0);
      group(s.target, 0.0);
      values.push_back(s.p);
      values.push_back(s.i);
      values.push_back(s.d);
      break;
  }
  return values;
}

std::string FormatValues(const std::vector<double>& values) {
  std::string out;
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) out += ",";
    out += Num(values[i]);
  }
  return out;
}

}  // namespace simpartner::sim
