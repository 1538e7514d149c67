#include "simpartner/teleop/mapping.h"

#include <SDL2/SDL_gamecontroller.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "simpartner/actuator_t.hpp"
#include "simpartner/bounded_file.h"
#include "simpartner/client/errors.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/model_message.h"

namespace simpartner::teleop {
namespace {

std::vector<std::string> Words(const std::string& line) {
  std::vector<std::string> words;
  std::istringstream in(line.substr(0, line.find('#')));
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

class Parser {
 public:
  Parser(std::string file, Diagnostics* diagnostics)
      : file_(std::move(file)), diagnostics_(diagnostics) {}

  void Error(int line, const std::string& message) {
    diagnostics_->push_back({file_, line, message});
  }

  bool Number(int line, const std::string& field, const std::string& text, double* out) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) {
      Error(line, field + ": '" + text + "' is not a finite number");
      return false;
    }
    *out = v;
    return true;
  }

  bool Axis(int line, const std::string& text, int* out) {
    const SDL_GameControllerAxis axis = SDL_GameControllerGetAxisFromString(text.c_str());
    if (axis == SDL_CONTROLLER_AXIS_INVALID) {
      std::string known;
      for (int a = 0; a < SDL_CONTROLLER_AXIS_MAX; ++a)
        known += std::string(a ? ", " : "") +
                 SDL_GameControllerGetStringForAxis(static_cast<SDL_GameControllerAxis>(a));
      Error(line, "axis '" + text + "' is not an SDL game controller axis (known: " + known + ")");
      return false;
    }
    *out = axis;
    return true;
  }

  bool Button(int line, const std::string& text, int* out) {
    const SDL_GameControllerButton button = SDL_GameControllerGetButtonFromString(text.c_str());
    if (button == SDL_CONTROLLER_BUTTON_INVALID) {
      std::string known;
      for (int b = 0; b < SDL_CONTROLLER_BUTTON_MAX; ++b)
        known += std::string(b ? ", " : "") +
                 SDL_GameControllerGetStringForButton(static_cast<SDL_GameControllerButton>(b));
      Error(line,
            "button '" + text + "' is not an SDL game controller button (known: " + known + ")");
      return false;
    }
    *out = button;
    return true;
  }

  bool Gains(int line, const std::vector<std::string>& w, size_t first, teleop::Gains* gains) {
    return Number(line, "fmax", w[first], &gains->fmax) &&
           Number(line, "P", w[first + 1], &gains->p) &&
           Number(line, "I", w[first + 2], &gains->i) &&
           Number(line, "D", w[first + 3], &gains->d) && Positive(line, "fmax", gains->fmax);
  }

  bool Positive(int line, const std::string& field, double v) {
    if (v > 0) return true;
    Error(line, field + " must be > 0 (is " + std::to_string(v) + ")");
    return false;
  }

 private:
  std::string file_;
  Diagnostics* diagnostics_;
};

// Rotates v by the unit quaternion q (w, x, y, z).
Eigen::Vector3d Rotate(const double q[4], const Eigen::Vector3d& v) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized() * v;
}

}  // namespace

std::string Diagnostic::ToString() const {
  return file + ":" + std::to_string(line) + ": " + message;
}

std::string JoinDiagnostics(const Diagnostics& diagnostics) {
  std::string out;
  for (const Diagnostic& d : diagnostics) out += (out.empty() ? "" : "\n") + d.ToString();
  return out;
}

MappingError::MappingError(Diagnostics diagnostics)
    : std::runtime_error(JoinDiagnostics(diagnostics)), diagnostics_(std::move(diagnostics)) {}

Mapping ParseMapping(const std::string& text, const std::string& file) {
  Mapping m;
  m.file = file;
  Diagnostics diagnostics;
  Parser p(file, &diagnostics);
  std::istringstream in(text);
  std::string line_text;
  int line = 0;
  std::set<std::string> level_names;
  while (std::getline(in, line_text)) {
    ++line;
    const std::vector<std::string> w = Words(line_text);
    if (w.empty()) continue;
    const std::string& key = w[0];
    auto arity = [&](size_t lo, size_t hi, const std::string& form) {
      if (w.size() >= lo + 1 && w.size() <= hi + 1) return true;
      p.Error(line, "'" + key + "' takes " + form + " (got " + std::to_string(w.size() - 1) +
                        " words)");
      return false;
    };
    if (key == "model") {
      if (w.size() < 2) {
        p.Error(line, "'model' takes the robot model name, e.g. model WorkPartner gen3");
        continue;
      }
      m.model = line_text.substr(line_text.find(w[1]));
      m.model = m.model.substr(0, m.model.find('#'));
      while (!m.model.empty() && std::isspace(static_cast<unsigned char>(m.model.back())))
        m.model.pop_back();
      m.model_line = line;
    } else if (key == "forward") {
      if (!arity(2, 2, "<body> <+x|-x|+y|-y|+z|-z>")) continue;
      static const std::map<std::string, int> kAxes = {{"x", 0}, {"y", 1}, {"z", 2}};
      const std::string& dir = w[2];
      if (dir.size() != 2 || (dir[0] != '+' && dir[0] != '-') || !kAxes.count(dir.substr(1))) {
        p.Error(line, "forward direction '" + dir + "' must be one of +x -x +y -y +z -z");
        continue;
      }
      m.forward_body = w[1];
      for (int& c : m.forward_axis) c = 0;
      m.forward_axis[kAxes.at(dir.substr(1))] = dir[0] == '+' ? 1 : -1;
      m.forward_line = line;
    } else if (key == "deadman") {
      if (!arity(1, 1, "<button>")) continue;
      m.deadman_line = line;  // present even if its name is wrong (said above)
      p.Button(line, w[1], &m.deadman_button);
    } else if (key == "deadzone") {
      if (!arity(1, 1, "<0..0.9>")) continue;
      double v = 0;
      if (!p.Number(line, "deadzone", w[1], &v)) continue;
      if (v < 0 || v > 0.9) {
        p.Error(line, "deadzone " + w[1] + " is outside 0..0.9");
        continue;
      }
      m.deadzone = v;
    } else if (key == "drive") {
      if (!arity(2, 2, "<axis> <scale rad/s>")) continue;
      m.drive_line = line;
      if (p.Axis(line, w[1], &m.drive_axis) &&
          p.Number(line, "drive scale", w[2], &m.drive_scale) && m.drive_scale == 0)
        p.Error(line, "drive scale 0 would never move the robot");
    } else if (key == "wheel") {
      if (!arity(1, 2, "<actuator> [<max force>]")) continue;
      Mapping::Wheel wheel;
      wheel.line = line;
      wheel.actuator = w[1];
      if (w.size() == 3 && !(p.Number(line, "max force", w[2], &wheel.max_force) &&
                             p.Positive(line, "max force", wheel.max_force)))
        continue;
      m.wheels.push_back(wheel);
    } else if (key == "steer") {
      if (!arity(7, 7, "<axis> <actuator> <scale rad> <fmax> <P> <I> <D>")) continue;
      Mapping::Steer steer;
      steer.line = line;
      steer.actuator = w[2];
      if (!p.Axis(line, w[1], &steer.axis) || !p.Number(line, "steer scale", w[3], &steer.scale) ||
          !p.Gains(line, w, 4, &steer.gains))
        continue;
      if (m.steer) p.Error(line, "a second 'steer' (the first is on line " +
                                     std::to_string(m.steer->line) + ")");
      m.steer = steer;
    } else if (key == "level") {
      if (!arity(10, 10, "<name> <button +> <button -> <step> <min> <max> <fmax> <P> <I> <D>"))
        continue;
      Mapping::Level level;
      level.line = line;
      level.name = w[1];
      if (!p.Button(line, w[2], &level.button_plus) || !p.Button(line, w[3], &level.button_minus) ||
          !p.Number(line, "step", w[4], &level.step) || !p.Number(line, "min", w[5], &level.min) ||
          !p.Number(line, "max", w[6], &level.max) || !p.Gains(line, w, 7, &level.gains))
        continue;
      if (!(level.step > 0)) p.Error(line, "level '" + level.name + "': step must be > 0");
      if (!(level.min <= 0 && 0 <= level.max && level.min < level.max))
        p.Error(line, "level '" + level.name + "': need min <= 0 <= max and min < max (0 is "
                      "the model's initial pose)");
      if (!level_names.insert(level.name).second)
        p.Error(line, "level '" + level.name + "' is defined twice");
      m.levels.push_back(level);
    } else if (key == "joint") {
      if (!arity(3, 3, "<level> <actuator> <factor>")) continue;
      Mapping::Joint joint;
      joint.line = line;
      joint.level = w[1];
      joint.actuator = w[2];
      if (!p.Number(line, "factor", w[3], &joint.factor)) continue;
      if (!level_names.count(joint.level))
        p.Error(line, "level '" + joint.level + "' is not defined above");
      m.joints.push_back(joint);
    } else {
      p.Error(line, "unknown statement '" + key +
                        "' (known: model, forward, deadman, deadzone, drive, wheel, steer, "
                        "level, joint)");
    }
  }
  if (m.deadman_line == 0) p.Error(0, "no 'deadman <button>': the dead-man button is required");
  if (m.drive_line == 0) p.Error(0, "no 'drive <axis> <scale>'");
  if (m.forward_line == 0) p.Error(0, "no 'forward <body> <axis>': the wheel signs need it");
  if (m.wheels.empty()) p.Error(0, "no 'wheel <actuator>'");
  if (!diagnostics.empty()) throw MappingError(diagnostics);
  return m;
}

Mapping LoadMapping(const std::string& path) {
  try {
    return ParseMapping(ReadBoundedFile(path, kMaxSettingsFileBytes, "mapping files"), path);
  } catch (const FileReadError& e) {
    throw MappingError(
        {{path, 0, e.cannot_open() ? std::string("cannot be read: ") + e.what() : e.what()}});
  }
}

std::string MappingFileFor(const std::string& model_name, const std::string& dir) {
  std::string base;
  for (char c : model_name) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      base += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!base.empty() && base.back() != '_')
      base += '_';
  }
  while (!base.empty() && base.back() == '_') base.pop_back();
  return dir + "/" + base + ".map";
}

Plan BuildPlan(const Mapping& mapping, const model_t& model) {
  Diagnostics diagnostics;
  auto error = [&](int line, const std::string& message) {
    diagnostics.push_back({mapping.file, line, message});
  };
  if (model.robots.empty()) throw MappingError({{mapping.file, 0, "the model has no robot"}});
  // The robot: the first whose model the mapping names, else the first.
  size_t robot = 0;
  bool found = mapping.model.empty();
  for (size_t r = 0; r < model.robots.size() && !found; ++r)
    if (model.robots[r].model == mapping.model) robot = r, found = true;
  if (!found) {
    std::string models;
    for (const robot_t& r : model.robots) models += (models.empty() ? "'" : ", '") + r.model + "'";
    error(mapping.model_line,
          "the mapping is for model '" + mapping.model + "'; the sim's robots are " + models);
    throw MappingError(diagnostics);
  }
  client::Catalog catalog;
  try {
    catalog = client::Catalog::FromModel(model);
  } catch (const client::ClientError& e) {
    throw MappingError({{mapping.file, 0, std::string("the model cannot be used: ") + e.what()}});
  }
  Plan plan;
  plan.mapping_file = mapping.file;
  plan.robot = model.robots[robot].name;
  plan.deadman_button = mapping.deadman_button;
  plan.deadzone = mapping.deadzone;
  plan.drive_axis = mapping.drive_axis;
  plan.drive_scale = mapping.drive_scale;
  const std::string robot_name = plan.robot;

  auto find = [&](int line, const std::string& name, int kind,
                  const char* kind_name) -> std::optional<client::Target> {
    try {
      const client::Target& t = catalog.Find(robot_name + "/" + name);
      if (!t.is_actuator() || t.lcm_kind != kind) {
        error(line, "'" + name + "' is a " + t.kind_name() + ", not a " + kind_name);
        return std::nullopt;
      }
      return t;
    } catch (const client::UnknownTarget& e) {
      error(line, "robot '" + robot_name + "' (" + model.robots[robot].model + ") has no actuator '" +
                      name + "'" +
                      (e.suggestions().empty() ? "" : " (did you mean '" + e.suggestions()[0] + "'?)"));
      return std::nullopt;
    }
  };

  // The forward direction in the world at step 0.
  Eigen::Vector3d forward = Eigen::Vector3d::Zero();
  bool have_forward = false;
  for (const body_t& b : model.bodies) {
    if (b.name != mapping.forward_body || b.robot != static_cast<int16_t>(robot)) continue;
    forward = Rotate(b.initial_orientation, Eigen::Vector3d(mapping.forward_axis[0],
                                                            mapping.forward_axis[1],
                                                            mapping.forward_axis[2]));
    have_forward = true;
  }
  if (!have_forward)
    error(mapping.forward_line, "robot '" + robot_name + "' has no body '" + mapping.forward_body + "'");
  const Eigen::Vector3d up(model.up[0], model.up[1], model.up[2]);

  for (const Mapping::Wheel& w : mapping.wheels) {
    auto target = find(w.line, w.actuator, actuator_t::KIND_JOINT_VELOCITY, "velocity controller");
    if (!target || !have_forward) continue;
    if (target->num_axes != 1 || target->joint_index < 0 ||
        static_cast<size_t>(target->joint_index) >= model.joints.size()) {
      error(w.line, "'" + w.actuator + "' drives a joint with " +
                        std::to_string(target->num_axes) + " axes; a wheel needs one");
      continue;
    }
    const joint_t& joint = model.joints[static_cast<size_t>(target->joint_index)];
    const Eigen::Vector3d axis(joint.axis[0][0], joint.axis[0][1], joint.axis[0][2]);
    const Eigen::Vector3d anchor(joint.anchor[0], joint.anchor[1], joint.anchor[2]);
    // The wheel is the body whose centre is at the axle (the other one, a
    // calf, hangs from it). The joint rate is body1 relative to body2, so
    // the wheel turns at +rate about the axis as body1 and -rate as body2.
    auto distance = [&](int32_t body) {
      if (body < 0 || static_cast<size_t>(body) >= model.bodies.size()) return 1e300;
      const double* p = model.bodies[static_cast<size_t>(body)].initial_position;
      return (Eigen::Vector3d(p[0], p[1], p[2]) - anchor).norm();
    };
    const int wheel_side = distance(joint.body1) <= distance(joint.body2) ? 1 : -1;
    // Rolling on the ground, a wheel spinning at omega about the axis moves
    // its centre by omega x (up * radius).
    const Eigen::Vector3d roll = wheel_side * axis.cross(up);
    const double along = roll.dot(forward.normalized());
    if (std::abs(along) < 0.5) {
      error(w.line, "'" + w.actuator + "' turns joint '" + joint.name +
                        "' whose axis does not roll the robot along its forward direction (" +
                        mapping.forward_body + "): a wheel's axle must be across it");
      continue;
    }
    plan.wheels.push_back({*target, along > 0 ? 1 : -1, w.max_force});
  }
  if (mapping.steer) {
    const Mapping::Steer& s = *mapping.steer;
    if (auto target = find(s.line, s.actuator, actuator_t::KIND_ANGLE, "angle controller"))
      plan.steer = Plan::Steer{*target, s.axis, s.scale, s.gains};
  }
  for (const Mapping::Level& l : mapping.levels) {
    Plan::Level level{l.name, l.button_plus, l.button_minus, l.step, l.min, l.max, l.gains, {}};
    for (const Mapping::Joint& j : mapping.joints) {
      if (j.level != l.name) continue;
      if (auto target = find(j.line, j.actuator, actuator_t::KIND_ANGLE, "angle controller"))
        level.joints.push_back({*target, j.factor});
    }
    if (level.joints.empty())
      error(l.line, "level '" + l.name + "' moves no joint (add 'joint " + l.name +
                        " <actuator> <factor>')");
    plan.levels.push_back(level);
  }
  if (!diagnostics.empty()) throw MappingError(diagnostics);
  return plan;
}

model_t ModelFromWorldFile(const std::string& world_path) {
  return model::ModelMessageFromWorld(model::LoadWorldOrThrow(world_path));
}

}  // namespace simpartner::teleop
