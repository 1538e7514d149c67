#include "simpartner/client/catalog.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "simpartner/actuator_t.hpp"
#include "simpartner/client/errors.h"
#include "simpartner/command_t.hpp"
#include "simpartner/sensor_kinds.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner::client {
namespace {

bool AllDigits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
}

// "robot/name" -> {robot, name}; "name" -> {"", name}.
std::pair<std::string, std::string> SplitQualified(const std::string& spec) {
  const size_t slash = spec.find('/');
  if (slash == std::string::npos) return {"", spec};
  return {spec.substr(0, slash), spec.substr(slash + 1)};
}

}  // namespace


std::string Target::kind_name() const {
  if (is_actuator()) {
    switch (lcm_kind) {
      case actuator_t::KIND_JOINT_VELOCITY: return "velocity controller";
      case actuator_t::KIND_ANGLE: return "angle controller";
      case actuator_t::KIND_LINEAR_MOTOR: return "linear motor";
      default: return "actuator kind " + std::to_string(lcm_kind);
    }
  }
  const SensorKindSpelling& kind = SpellSensorKind(lcm_kind);
  return kind.kind < 0 ? "sensor kind " + std::to_string(lcm_kind) : kind.word;
}

CommandTargetShape Target::shape() const {
  CommandTargetShape shape;
  shape.is_sensor = is_sensor();
  shape.kind = lcm_kind;
  shape.num_axes = num_axes;
  return shape;
}

Catalog Catalog::FromModel(const model_t& model) {
  Catalog catalog;
  catalog.simulation_id_ = model.simulation_id;
  catalog.step_size_ = model.step_size;
  catalog.state_every_ = std::max(1, model.state_every);
  catalog.world_name_ = model.world_name;
  catalog.world_file_ = model.world_file;
  for (const robot_t& robot : model.robots) {
    catalog.robot_names_.push_back(robot.name);
    catalog.robot_models_.push_back(robot.model);
  }
  auto robot_name = [&](int robot, const std::string& what) -> std::string {
    if (robot < 0) return "";
    if (static_cast<size_t>(robot) >= catalog.robot_names_.size())
      throw ClientError("SIM_MODEL: " + what + " names robot " + std::to_string(robot) +
                        " of " + std::to_string(catalog.robot_names_.size()));
    return catalog.robot_names_[static_cast<size_t>(robot)];
  };
  for (const joint_t& joint : model.joints) {
    catalog.joint_names_.push_back(joint.name);
    catalog.joint_robots_.push_back(robot_name(joint.robot, "joint '" + joint.name + "'"));
  }
  for (const body_t& body : model.bodies) {
    catalog.body_names_.push_back(body.name);
    catalog.body_robots_.push_back(robot_name(body.robot, "body '" + body.name + "'"));
  }
  auto joint_name = [&](int joint, const std::string& what) -> std::string {
    if (joint < 0) return "";
    if (static_cast<size_t>(joint) >= model.joints.size())
      throw ClientError("SIM_MODEL: " + what + " names joint " + std::to_string(joint) + " of " +
                        std::to_string(model.joints.size()));
    return model.joints[static_cast<size_t>(joint)].name;
  };
  for (size_t i = 0; i < model.actuators.size(); ++i) {
    const actuator_t& a = model.actuators[i];
    Target t;
    t.kind = TargetKind::kActuator;
    t.robot = robot_name(a.robot, "actuator '" + a.name + "'");
    t.name = a.name;
    t.port = a.port;
    t.index = static_cast<int>(i);
    t.lcm_kind = a.kind;
    t.num_axes = a.num_axes;
    t.axis_slot[0] = a.axis_slot[0];
    t.axis_slot[1] = a.axis_slot[1];
    t.joint = joint_name(a.joint, "actuator '" + a.name + "'");
    t.joint_index = a.joint;
    catalog.targets_.push_back(t);
  }
  for (size_t i = 0; i < model.sensors.size(); ++i) {
    const sensor_t& s = model.sensors[i];
    Target t;
    t.kind = TargetKind::kSensor;
    t.robot = robot_name(s.robot, "sensor '" + s.name + "'");
    t.name = s.name;
    t.port = s.port;
    t.index = static_cast<int>(i);
    t.lcm_kind = s.kind;
    t.joint = joint_name(s.joint, "sensor '" + s.name + "'");
    t.joint_index = s.joint;
    catalog.targets_.push_back(t);
  }
  for (size_t k = 0; k < catalog.targets_.size(); ++k) {
    if (catalog.targets_[k].port > 0) catalog.by_port_.emplace(catalog.targets_[k].port, k);
  }
  return catalog;
}

const Target* Catalog::TryFind(const std::string& spec) const {
  const auto [robot, name] = SplitQualified(spec);
  const Target* found = nullptr;
  for (const Target& t : targets_) {
    if (t.name != name || (!robot.empty() && t.robot != robot)) continue;
    if (found) return nullptr;  // ambiguous
    found = &t;
  }
  return found;
}

const Target& Catalog::Find(const std::string& spec) const {
  const auto [robot, name] = SplitQualified(spec);
  std::vector<const Target*> found;
  for (const Target& t : targets_) {
    if (t.name == name && (robot.empty() || t.robot == robot)) found.push_back(&t);
  }
  if (found.size() == 1) return *found.front();
  if (found.empty()) {
    if (!robot.empty() &&
        std::find(robot_names_.begin(), robot_names_.end(), robot) == robot_names_.end()) {
      std::vector<std::string> robots;
      for (const std::string& r : robot_names_)
        if (EditDistance(r, robot) <= std::max<size_t>(2, robot.size() / 3)) robots.push_back(r);
      throw UnknownTarget(spec, robots, "robot '" + robot + "' of '" + spec +
                                             "' is not in the model");
    }
    throw UnknownTarget(spec, Suggest(spec));
  }
  std::vector<std::string> qualified;
  for (const Target* t : found) qualified.push_back(t->qualified_name());
  throw UnknownTarget(spec, qualified,
                      "'" + spec + "' names " + std::to_string(found.size()) +
                          " targets in different robots; qualify it as robot/name");
}

const Target& Catalog::FindByPort(int port) const {
  const auto it = by_port_.find(port);
  if (it != by_port_.end()) return targets_[it->second];
  std::vector<std::string> ports;
  std::vector<std::pair<int, int>> nearest;  // distance, port
  for (const auto& [p, k] : by_port_) nearest.emplace_back(std::abs(p - port), p);
  std::sort(nearest.begin(), nearest.end());
  for (size_t k = 0; k < nearest.size() && k < 3; ++k) {
    const Target& t = targets_[by_port_.at(nearest[k].second)];
    ports.push_back(std::to_string(nearest[k].second) + " (" + t.name + ")");
  }
  throw UnknownTarget(std::to_string(port), ports,
                      "port " + std::to_string(port) + " is not an actuator or sensor of the model");
}

const Target& Catalog::Resolve(const std::string& name_or_port) const {
  if (AllDigits(name_or_port) && name_or_port.size() < 7)
    return FindByPort(std::stoi(name_or_port));
  return Find(name_or_port);
}

std::vector<std::string> Catalog::Suggest(const std::string& spec, size_t max) const {
  const auto [robot, name] = SplitQualified(spec);
  std::vector<std::pair<size_t, std::string>> scored;
  for (const Target& t : targets_) {
    if (!robot.empty() && t.robot != robot) continue;
    size_t same_name = 0;
    for (const Target& u : targets_) same_name += u.name == t.name ? 1 : 0;
    const std::string shown = same_name > 1 || !robot.empty() ? t.qualified_name() : t.name;
    scored.emplace_back(EditDistance(name, t.name), shown);
  }
  std::sort(scored.begin(), scored.end());
  scored.erase(std::unique(scored.begin(), scored.end()), scored.end());
  // Only names reasonably close: at most a third of the name changed, or
  // a difference in case.
  const size_t limit = std::max<size_t>(2, name.size() / 3);
  std::vector<std::string> out;
  for (const auto& [distance, shown] : scored) {
    if (out.size() >= max || distance > limit) break;
    out.push_back(shown);
  }
  return out;
}

int Catalog::IndexByName(const std::vector<std::string>& names,
                         const std::vector<std::string>& robots, const std::string& what,
                         const std::string& spec) const {
  const auto [robot, name] = SplitQualified(spec);
  int found = -1;
  int count = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] != name || (!robot.empty() && robots[i] != robot)) continue;
    if (found < 0) found = static_cast<int>(i);
    ++count;
  }
  if (count == 1) return found;
  if (count > 1)
    throw UnknownTarget(spec, {}, "the " + what + " '" + spec +
                                      "' exists in several robots; qualify it as robot/name");
  std::vector<std::pair<size_t, std::string>> scored;
  for (const std::string& n : names) scored.emplace_back(EditDistance(name, n), n);
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> suggestions;
  for (const auto& [distance, n] : scored) {
    if (suggestions.size() >= 3 || distance > std::max<size_t>(2, name.size() / 3)) break;
    if (std::find(suggestions.begin(), suggestions.end(), n) == suggestions.end())
      suggestions.push_back(n);
  }
  throw UnknownTarget(spec, suggestions, "'" + spec + "' is not a " + what + " of the model");
}

int Catalog::JointIndex(const std::string& name) const {
  return IndexByName(joint_names_, joint_robots_, "joint", name);
}

int Catalog::BodyIndex(const std::string& name) const {
  return IndexByName(body_names_, body_robots_, "body", name);
}

int64_t Catalog::StepAt(double sim_time) const {
  if (step_size_ <= 0) return 0;
  return static_cast<int64_t>(std::llround(sim_time / step_size_));
}

std::string Catalog::DescribeValueForms(const Target& target) const {
  std::string out;
  const CommandTargetShape shape = target.shape();
  const int actions[] = {command_t::ACTION_SET, command_t::ACTION_HOLD,
                         command_t::ACTION_SET_STOPS, command_t::ACTION_SENSOR_PARAMS,
                         command_t::ACTION_READ};
  for (int action : actions) {
    const std::string forms = simpartner::DescribeValueForms(shape, action);
    if (forms.empty()) continue;
    if (!out.empty()) out += "; ";
    out += std::string(ActionName(action)) + ": " + forms;
  }
  if (out.empty() && target.is_sensor())  // a camera: no command at all
    out = CheckValueCount(shape, command_t::ACTION_READ, 0);
  return out;
}

std::string Catalog::Describe() const {
  std::ostringstream out;
  out << "world " << world_name_ << " (" << world_file_ << "), simulation " << simulation_id_
      << ", step " << step_size_ << " s, SIM_STATE every " << state_every_ << " step(s)\n";
  for (size_t r = 0; r < robot_names_.size(); ++r) {
    out << "robot " << robot_names_[r] << " (" << robot_models_[r] << ")\n";
    for (int pass = 0; pass < 2; ++pass) {
      const bool sensors = pass == 1;
      out << (sensors ? "  sensors:\n" : "  actuators:\n");
      for (const Target& t : targets_) {
        if (t.robot != robot_names_[r] || t.is_sensor() != sensors) continue;
        out << "    " << t.name << "  " << t.kind_name();
        if (t.port > 0) out << ", port " << t.port;
        if (!t.joint.empty()) out << ", joint " << t.joint;
        if (t.is_actuator()) {
          out << " (" << t.num_axes << (t.num_axes == 1 ? " axis" : " axes");
          const char* slots = "xyz";
          for (int a = 0; a < t.num_axes && a < 2; ++a)
            out << (a ? "," : ", slot ") << slots[t.axis_slot[a] % 3];
          out << ")";
        }
        out << "\n      " << DescribeValueForms(t) << "\n";
      }
    }
  }
  return out.str();
}

}  // namespace simpartner::client
