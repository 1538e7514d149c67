#include "simpartner/sim/controllers.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "simpartner/command_t.hpp"
#include "simpartner/text.h"

namespace simpartner::sim {
namespace {

double WrapAngle(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a < 0) a += 2.0 * M_PI;
  return a - M_PI;
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

namespace {

// What one value of a command sets, for messages and for the checks of the
// slots a joint does not use.
enum class ValueKind { kForce, kVelocity, kPosition, kGain };
struct ValueMeaning {
  std::string name;              // "max force, x slot"
  ValueKind kind = ValueKind::kForce;
  bool unused = false;           // a slot of the long form the joint has no axis for
};

// The meaning of every value of an actuator command of `count` values, or
// an empty list when count fits neither form (the caller reports that).
std::vector<ValueMeaning> CommandLayout(int action, model::ActuatorKind kind,
                                        const model::FlatJoint& joint, size_t count) {
  const int n = joint.num_axes;
  const char* kSlotNames = "xyz";
  std::string used_slots;
  for (int a = 0; a < n; ++a) used_slots += std::string(used_slots.empty() ? "" : ", ") +
                                            kSlotNames[joint.slot[a]];
  auto slot_meaning = [&](const std::string& group, ValueKind value_kind, int slot) {
    ValueMeaning m{group + ", " + kSlotNames[slot] + " slot", value_kind, true};
    for (int a = 0; a < n; ++a)
      if (joint.slot[a] == slot) m.unused = false;
    if (m.unused)
      m.name += ", unused: joint '" + joint.name + "' has " +
                (n == 0 ? std::string("no axis") : "slot " + used_slots + " only");
    return m;
  };
  auto axis_meaning = [&](const std::string& group, ValueKind value_kind, int a) {
    return ValueMeaning{n > 1 ? group + ", axis " + std::to_string(a + 1) : group, value_kind,
                        false};
  };
  // Groups of per-axis values, then any gains.
  std::vector<std::pair<std::string, ValueKind>> groups;
  bool gains = false;
  bool stops = false;
  switch (action) {
    case command_t::ACTION_SET:
      groups.emplace_back("max force", ValueKind::kForce);
      if (kind == model::ActuatorKind::kAngle) {
        groups.emplace_back("target angle", ValueKind::kPosition);
        gains = true;
      } else {
        groups.emplace_back("velocity", ValueKind::kVelocity);
      }
      break;
    case command_t::ACTION_HOLD: groups.emplace_back("max force", ValueKind::kForce); break;
    case command_t::ACTION_SET_STOPS: stops = true; break;
    default: return {};
  }
  const size_t per_group = stops ? 2 : 1;
  const size_t group_count = stops ? 1 : groups.size();
  const size_t tail = gains ? 3 : 0;
  const size_t long_form = 3 * per_group * group_count + tail;
  const size_t short_form = static_cast<size_t>(n) * per_group * group_count + tail;
  std::vector<ValueMeaning> layout;
  if (count != long_form && count != short_form) return layout;
  const bool slot_form = count == long_form;
  const int places = slot_form ? 3 : n;
  if (stops) {
    // lo, hi per slot (long form) or per axis (short form).
    for (int p = 0; p < places; ++p) {
      for (const char* bound : {"low stop", "high stop"})
        layout.push_back(slot_form ? slot_meaning(bound, ValueKind::kPosition, p)
                                   : axis_meaning(bound, ValueKind::kPosition, p));
    }
  } else {
    for (const auto& [group, value_kind] : groups) {
      for (int p = 0; p < places; ++p)
        layout.push_back(slot_form ? slot_meaning(group, value_kind, p)
                                   : axis_meaning(group, value_kind, p));
    }
  }
  if (gains) {
    for (const char* gain : {"P gain", "I gain", "D gain"})
      layout.push_back(ValueMeaning{gain, ValueKind::kGain, false});
  }
  return layout;
}

}  // namespace

ParsedCommand ParseActuatorCommand(int action, const std::vector<double>& v,
                                   model::ActuatorKind kind, const model::FlatJoint& joint,
                                   const ActuatorSetting& current) {
  ParsedCommand parsed;
  parsed.setting = current;
  const int n = joint.num_axes;
  const bool rotational = IsRotational(joint.source->kind);
  std::string& error = parsed.error;

  const std::vector<ValueMeaning> layout = CommandLayout(action, kind, joint, v.size());
  for (size_t k = 0; k < v.size(); ++k) {
    if (!std::isfinite(v[k])) {
      error = "values[" + std::to_string(k) + "] = " + FormatNumber(v[k], 10) + " is not a finite number";
      if (k < layout.size()) error += " (" + layout[k].name + ")";
      return parsed;
    }
  }
  // A slot the joint does not use sets nothing, but a value there is still
  // held to the range of its kind: 1e308 in the x slot of a wheel's
  // "1000,1000,100,0,0,0.2" is a broken sender, not a no-op.
  for (size_t k = 0; k < layout.size(); ++k) {
    if (!layout[k].unused) continue;
    double lo = 0.0, hi = 0.0;
    std::string unit;
    switch (layout[k].kind) {
      case ValueKind::kForce: lo = 0.0; hi = kMaxMotorForce; break;
      case ValueKind::kVelocity: lo = -kMaxMotorVelocity; hi = kMaxMotorVelocity; break;
      case ValueKind::kPosition:
        lo = rotational ? -M_PI : -kMaxSliderPosition;
        hi = rotational ? M_PI : kMaxSliderPosition;
        unit = rotational ? " rad" : " m";
        break;
      case ValueKind::kGain: lo = 0.0; hi = kMaxGain; break;
    }
    if (v[k] < lo || v[k] > hi) {
      error = "values[" + std::to_string(k) + "] (" + layout[k].name + ") = " + FormatNumber(v[k], 10) +
              unit + " is out of range [" + FormatNumber(lo, 10) + ", " + FormatNumber(hi, 10) + "]";
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
      error = field(index) + " (max force) = " + FormatNumber(v[index], 10) + " is out of range [0, " +
              FormatNumber(kMaxMotorForce, 10) + "]";
    return error.empty();
  };
  auto check_position = [&](size_t index, const char* what, int a) {
    const double x = v[index];
    const double lo = joint.source->lo_stop[a], hi = joint.source->hi_stop[a];
    if (rotational && (x < -M_PI || x > M_PI)) {
      error = field(index) + " (" + what + ") = " + FormatNumber(x, 10) + " rad is outside [-pi, pi]";
    } else if (x < lo || x > hi) {
      error = field(index) + " (" + what + ") = " + FormatNumber(x, 10) + " is outside joint '" + joint.name +
              "' range [" + FormatNumber(lo, 10) + ", " + FormatNumber(hi, 10) + "]";
    } else if (!rotational && std::abs(x) > kMaxSliderPosition) {
      error = field(index) + " (" + what + ") = " + FormatNumber(x, 10) + " m is out of range";
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
          if (v[g + k] < 0.0 || v[g + k] > kMaxGain) {
            error = field(g + k) + " (" + names[k] + " gain) = " + FormatNumber(v[g + k], 10) +
                    " is out of range [0, " + FormatNumber(kMaxGain, 10) + "]";
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
            error = field(vi) + " (velocity) = " + FormatNumber(v[vi], 10) + " is out of range [-" +
                    FormatNumber(kMaxMotorVelocity, 10) + ", " + FormatNumber(kMaxMotorVelocity, 10) + "]";
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
          error = field(base) + " (low stop) = " + FormatNumber(v[base], 10) + " is above " + field(base + 1) +
                  " (high stop) = " + FormatNumber(v[base + 1], 10);
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

std::vector<double> SettingToSlotValues(const ActuatorSetting& s, const model::FlatJoint& joint) {
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
    out += FormatNumber(values[i], 10);
  }
  return out;
}

}  // namespace simpartner::sim
