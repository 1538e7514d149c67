// What a sim offers to control code, built from its SIM_MODEL: every
// actuator and sensor as a Target addressable by name, robot/name or
// legacy port, plus the joint and body names the state is indexed by.
// Pure data, no transport: the sequencer's offline --check and the
// validation build one from a model_t of their own.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "simpartner/command_shape.h"
#include "simpartner/edit_distance.h"
#include "simpartner/model_t.hpp"

namespace simpartner::client {

enum class TargetKind { kActuator, kSensor };

struct Target {
  TargetKind kind = TargetKind::kActuator;
  std::string robot;   // robot instance name (model_t.robots[].name)
  std::string name;    // unique within its robot
  int port = 0;        // legacy port, 0 if none
  int index = -1;      // into model_t.actuators or model_t.sensors
  int lcm_kind = 0;    // actuator_t::KIND_* or sensor_t::KIND_*
  int num_axes = 0;    // axes of the driven joint (actuators), 0 for sensors
  int axis_slot[2] = {0, 0};  // slot (0 x, 1 y, 2 z) of each axis in the three-slot form
  std::string joint;   // joint driven (actuator) or measured (force/torque), else ""
  int joint_index = -1;

  bool is_actuator() const { return kind == TargetKind::kActuator; }
  bool is_sensor() const { return kind == TargetKind::kSensor; }
  std::string qualified_name() const { return robot + "/" + name; }
  // "velocity controller", "angle controller", "linear motor", "scanner", ...
  std::string kind_name() const;
  CommandTargetShape shape() const;
};

class Catalog {
 public:
  Catalog() = default;
  // Throws ClientError when the model contradicts itself (an index out of
  // range); duplicate names across robots are fine (qualify them).
  static Catalog FromModel(const model_t& model);

  // "name" or "robot/name". Throws UnknownTarget (with did-you-mean) when
  // absent, or when an unqualified name exists in several robots (the
  // message lists the qualified names).
  const Target& Find(const std::string& name) const;
  // Legacy port of the original (> 1024). Throws UnknownTarget.
  const Target& FindByPort(int port) const;
  // Either: an all-digit spec is a port, anything else a name.
  const Target& Resolve(const std::string& name_or_port) const;
  // nullptr instead of throwing.
  const Target* TryFind(const std::string& name) const;

  // Up to `max` target names nearest to `name` by edit distance
  // (qualified where the short name is ambiguous), nearest first.
  std::vector<std::string> Suggest(const std::string& name, size_t max = 3) const;

  // Joint and body indices into state_t.joints / state_t.bodies by "name"
  // or "robot/name" (world objects: their name). Throw UnknownTarget.
  int JointIndex(const std::string& name) const;
  int BodyIndex(const std::string& name) const;
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  const std::vector<std::string>& body_names() const { return body_names_; }

  // The forms of values a target takes, one line per action, e.g.
  // "set: fmax_x,fmax_y,fmax_z,vel_x,vel_y,vel_z (6) or fmax,vel (2)".
  std::string DescribeValueForms(const Target& target) const;
  // The whole model for simpartner-cmd model: robots, actuators with kind,
  // port and value forms, sensors.
  std::string Describe() const;

  const std::vector<Target>& targets() const { return targets_; }
  int64_t simulation_id() const { return simulation_id_; }
  double step_size() const { return step_size_; }
  int state_every() const { return state_every_; }
  const std::string& world_name() const { return world_name_; }
  const std::string& world_file() const { return world_file_; }
  const std::vector<std::string>& robot_names() const { return robot_names_; }
  const std::vector<std::string>& robot_models() const { return robot_models_; }
  // Step at or after sim time t [s] (rounded to the nearest step).
  int64_t StepAt(double sim_time) const;

 private:
  int IndexByName(const std::vector<std::string>& names, const std::vector<std::string>& robots,
                  const std::string& what, const std::string& name) const;

  std::vector<Target> targets_;
  std::map<int, size_t> by_port_;
  int64_t simulation_id_ = 0;
  double step_size_ = 0.0;
  int state_every_ = 1;
  std::string world_name_, world_file_;
  std::vector<std::string> robot_names_, robot_models_;
  std::vector<std::string> joint_names_, joint_robots_;  // robot "" for world joints
  std::vector<std::string> body_names_, body_robots_;
};

// Edit distance (Levenshtein, case-insensitive) for did-you-mean.
using ::simpartner::EditDistance;

}  // namespace simpartner::client
