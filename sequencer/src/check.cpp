#include "simpartner/sequencer/check.h"

#include <cmath>

#include "simpartner/actuator_t.hpp"
#include "simpartner/client/command.h"
#include "simpartner/client/errors.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner::sequencer {
namespace {

// How many values a reading of this sensor has (scanner: its rays).
int ReadingSize(const sensor_t& sensor) {
  switch (sensor.kind) {
    case sensor_t::KIND_POSITION: return 7;
    case sensor_t::KIND_VELOCITY: return 6;
    case sensor_t::KIND_FORCE_TORQUE: return 6;
    case sensor_t::KIND_SCANNER:
      return sensor.num_params > 0 ? static_cast<int>(sensor.params[0]) : 11;
    default: return 0;  // echo: text only
  }
}

std::string Qualified(const std::string& robot, const std::string& name) {
  return robot.empty() ? name : robot + "/" + name;
}

}  // namespace

DiagnosticList CheckSequence(const Sequence& sequence, const model_t& model, Plan* plan) {
  DiagnosticList diagnostics;
  client::Catalog catalog;
  try {
    catalog = client::Catalog::FromModel(model);
  } catch (const client::ClientError& e) {
    diagnostics.Add(sequence.file, 0, "", std::string("the model cannot be used: ") + e.what());
    return diagnostics;
  }
  Plan out;
  auto add = [&](int line, const std::string& element, const std::string& message) {
    diagnostics.Add(sequence.file, line, element, message);
  };
  auto robot_of = [&](const std::string& robot) {
    return robot.empty() ? sequence.robot : robot;
  };
  if (!sequence.robot.empty()) {
    bool known = false;
    for (const std::string& r : catalog.robot_names()) known |= r == sequence.robot;
    if (!known) {
      std::string robots;
      for (const std::string& r : catalog.robot_names()) robots += (robots.empty() ? "'" : ", '") + r + "'";
      add(sequence.line, "sequence", "robot '" + sequence.robot + "' is not in the model (it has " +
                                         (robots.empty() ? std::string("none") : robots) + ")");
    }
  }
  for (const Segment& segment : sequence.segments) {
    PlannedSegment planned;
    planned.source = &segment;
    for (const Command& c : segment.commands) {
      PlannedCommand p;
      p.source = &c;
      try {
        p.target = c.target.empty() ? catalog.FindByPort(c.port)
                                    : catalog.Find(Qualified(robot_of(c.robot), c.target));
      } catch (const client::UnknownTarget& e) {
        add(c.line, c.element, e.what());
        continue;
      }
      int8_t action = c.action;
      if (action == kOriginal) {
        // The original's command string to whatever has the port.
        if (p.target.is_actuator() || p.target.lcm_kind == sensor_t::KIND_ECHO)
          action = command_t::ACTION_SET;
        else
          action = c.text.empty() ? command_t::ACTION_READ : command_t::ACTION_SENSOR_PARAMS;
      }
      try {
        p.message = client::BuildCommandFromText(p.target, action, c.text);
      } catch (const client::ClientError& e) {
        add(c.line, c.element, e.what());
        continue;
      }
      planned.commands.push_back(std::move(p));
    }
    if (segment.wait) {
      const Wait& w = *segment.wait;
      planned.wait.source = &w;
      if (w.kind == Wait::Kind::kJoint) {
        const std::string name = Qualified(robot_of(w.robot), w.joint);
        try {
          planned.wait.joint = catalog.JointIndex(name);
          const joint_t& joint = model.joints[static_cast<size_t>(planned.wait.joint)];
          if (w.axis >= std::max<int>(1, joint.num_axes))
            add(w.line, "wait", "joint '" + w.joint + "' has " + std::to_string(joint.num_axes) +
                                    " axes; axis " + std::to_string(w.axis) + " does not exist");
        } catch (const client::ClientError& e) {
          add(w.line, "wait", e.what());
        }
      } else if (w.kind == Wait::Kind::kSensor) {
        try {
          const client::Target& t = catalog.Find(Qualified(robot_of(w.robot), w.sensor));
          if (!t.is_sensor()) {
            add(w.line, "wait", "'" + w.sensor + "' is an actuator (" + t.kind_name() +
                                    "), not a sensor");
          } else {
            const sensor_t& sensor = model.sensors[static_cast<size_t>(t.index)];
            const int size = ReadingSize(sensor);
            if (w.index >= size)
              add(w.line, "wait", "sensor '" + w.sensor + "' (" + t.kind_name() + ") reads " +
                                      std::to_string(size) + " values; index " +
                                      std::to_string(w.index) + " does not exist");
            planned.wait.sensor = t.index;
            planned.wait.sensor_name = t.name;
            planned.wait.read_on_request = !(sensor.rate > 0);
          }
        } catch (const client::ClientError& e) {
          add(w.line, "wait", e.what());
        }
      }
    }
    out.segments.push_back(std::move(planned));
  }
  for (const client::Target& t : catalog.targets())
    if (t.is_actuator() && t.lcm_kind == actuator_t::KIND_JOINT_VELOCITY)
      out.wheel_motors.push_back(t);
  if (diagnostics.empty() && plan != nullptr) *plan = std::move(out);
  return diagnostics;
}

model_t ModelFromWorld(const model::World& world) {
  model_t m{};
  m.world_file = world.file;
  m.world_name = world.name;
  m.step_size = 0.001;
  m.state_every = 1;
  for (const model::Body& b : world.objects) {
    body_t body{};
    body.name = b.name;
    body.robot = -1;
    m.bodies.push_back(body);
  }
  for (const model::Joint& j : world.joints) {
    joint_t joint{};
    joint.name = j.name;
    joint.robot = -1;
    joint.num_axes = static_cast<int8_t>(model::AxisCount(j.kind));
    m.joints.push_back(joint);
  }
  for (size_t r = 0; r < world.robots.size(); ++r) {
    const model::RobotInstance& instance = world.robots[r];
    const int16_t robot_index = static_cast<int16_t>(r);
    robot_t robot{};
    robot.name = instance.name;
    robot.model = instance.robot.model_name;
    robot.file = instance.file;
    robot.total_mass = instance.robot.TotalMass();
    m.robots.push_back(robot);
    const int32_t first_joint = static_cast<int32_t>(m.joints.size());
    for (const model::Body& b : instance.robot.bodies) {
      body_t body{};
      body.name = b.name;
      body.robot = robot_index;
      m.bodies.push_back(body);
    }
    for (const model::Joint& j : instance.robot.joints) {
      joint_t joint{};
      joint.name = j.name;
      joint.robot = robot_index;
      joint.num_axes = static_cast<int8_t>(model::AxisCount(j.kind));
      m.joints.push_back(joint);
    }
    auto joint_index = [&](const std::string& name) -> int32_t {
      for (size_t k = 0; k < instance.robot.joints.size(); ++k)
        if (instance.robot.joints[k].name == name) return first_joint + static_cast<int32_t>(k);
      return -1;
    };
    for (const model::Actuator& a : instance.robot.actuators) {
      actuator_t actuator{};
      actuator.id = static_cast<int32_t>(m.actuators.size());
      actuator.name = a.name;
      actuator.robot = robot_index;
      actuator.kind = static_cast<int8_t>(a.kind);
      actuator.joint = joint_index(a.joint);
      actuator.port = a.port;
      const model::Joint* joint = instance.robot.FindJoint(a.joint);
      actuator.num_axes = static_cast<int8_t>(joint ? model::AxisCount(joint->kind) : 0);
      for (int axis = 0; axis < 2 && joint; ++axis) {
        const Eigen::Vector3d direction = instance.placement.linear() * joint->axis[axis];
        Eigen::Index slot = 0;
        direction.cwiseAbs().maxCoeff(&slot);
        actuator.axis_slot[axis] = static_cast<int8_t>(slot);
      }
      m.actuators.push_back(actuator);
    }
    for (const model::Sensor& s : instance.robot.sensors) {
      sensor_t sensor{};
      sensor.id = static_cast<int32_t>(m.sensors.size());
      sensor.name = s.name;
      sensor.robot = robot_index;
      sensor.kind = static_cast<int8_t>(s.kind);
      sensor.body = -1;
      sensor.joint = s.joint.empty() ? -1 : joint_index(s.joint);
      sensor.port = s.port;
      sensor.rate = s.rate;
      if (s.kind == model::SensorKind::kScanner)
        sensor.params = {static_cast<double>(s.rays), s.half_span, s.range};
      sensor.num_params = static_cast<int32_t>(sensor.params.size());
      m.sensors.push_back(sensor);
    }
  }
  m.num_robots = static_cast<int16_t>(m.robots.size());
  m.num_bodies = static_cast<int32_t>(m.bodies.size());
  m.num_joints = static_cast<int32_t>(m.joints.size());
  m.num_sensors = static_cast<int32_t>(m.sensors.size());
  m.num_actuators = static_cast<int32_t>(m.actuators.size());
  return m;
}

}  // namespace simpartner::sequencer
