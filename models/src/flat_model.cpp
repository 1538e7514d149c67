#include "simpartner/model/flat_model.h"

#include <cmath>
#include <functional>

namespace simpartner::model {
namespace {

// Index of the coordinate axis most aligned with axis, skipping taken.
int AlignedSlot(const Eigen::Vector3d& axis, int taken) {
  int best = -1;
  double best_alignment = -1.0;
  for (int i = 0; i < 3; ++i) {
    if (i == taken) continue;
    const double alignment = std::abs(axis[i]);
    if (alignment > best_alignment + 1e-12) {
      best_alignment = alignment;
      best = i;
    }
  }
  return best;
}

template <class Item, class Pred>
int FindIndex(const std::vector<Item>& items, const World& world, const std::string& robot,
              const std::string& name, Pred&& extra) {
  for (size_t i = 0; i < items.size(); ++i) {
    const Item& item = items[i];
    if (item.name != name || !extra(item)) continue;
    if (!robot.empty()) {
      if (item.robot < 0 || world.robots[item.robot].name != robot) continue;
    }
    return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

int FlatModel::FindActuator(const std::string& robot, const std::string& name) const {
  return FindIndex(actuators, *world, robot, name, [](const FlatActuator&) { return true; });
}
int FlatModel::FindSensor(const std::string& robot, const std::string& name) const {
  return FindIndex(sensors, *world, robot, name, [](const FlatSensor&) { return true; });
}
int FlatModel::FindBody(const std::string& robot, const std::string& name) const {
  return FindIndex(bodies, *world, robot, name, [](const FlatBody&) { return true; });
}
int FlatModel::FindJoint(const std::string& robot, const std::string& name) const {
  return FindIndex(joints, *world, robot, name, [](const FlatJoint&) { return true; });
}
int FlatModel::FindActuatorByPort(int port) const {
  for (size_t i = 0; i < actuators.size(); ++i)
    if (port != 0 && actuators[i].source->port == port) return static_cast<int>(i);
  return -1;
}
int FlatModel::FindSensorByPort(int port) const {
  for (size_t i = 0; i < sensors.size(); ++i)
    if (port != 0 && sensors[i].source->port == port) return static_cast<int>(i);
  return -1;
}

FlatModel Flatten(const World& world) {
  FlatModel flat;
  flat.world = &world;
  for (const Body& b : world.objects) {
    FlatBody body;
    body.name = b.name;
    body.source = &b;
    body.pose = b.pose;
    body.linear_velocity = b.linear_velocity;
    body.angular_velocity = b.angular_velocity;
    flat.bodies.push_back(body);
  }
  auto add_joint = [&flat](const Joint& j, int robot, int body_offset,
                           const std::function<int(const std::string&)>& body_index,
                           const Eigen::Isometry3d& frame) {
    FlatJoint joint;
    joint.name = j.name;
    joint.robot = robot;
    joint.source = &j;
    joint.body1 = body_index(j.body1);
    joint.body2 = body_index(j.body2);
    joint.anchor = frame * j.anchor;
    joint.num_axes = model::AxisCount(j.kind);
    int taken = -1;
    for (int a = 0; a < 2; ++a) {
      joint.axis[a] = frame.linear() * j.axis[a];
      // Slots follow the robot's own axes (the file's frame), not the world.
      joint.slot[a] = AlignedSlot(j.axis[a], taken);
      if (a < joint.num_axes) taken = joint.slot[a];
    }
    (void)body_offset;
    flat.joints.push_back(joint);
  };
  const int object_count = static_cast<int>(world.objects.size());
  for (const Joint& j : world.joints) {
    add_joint(j, -1, 0,
              [&](const std::string& name) {
                for (int i = 0; i < object_count; ++i)
                  if (world.objects[i].name == name) return i;
                return -1;  // "world"
              },
              Eigen::Isometry3d::Identity());
  }
  for (size_t r = 0; r < world.robots.size(); ++r) {
    const model::RobotInstance& instance = world.robots[r];
    const int first_body = static_cast<int>(flat.bodies.size());
    for (const Body& b : instance.robot.bodies) {
      FlatBody body;
      body.name = b.name;
      body.robot = static_cast<int>(r);
      body.source = &b;
      body.pose = instance.placement * b.pose;
      flat.bodies.push_back(body);
    }
    auto body_index = [&](const std::string& name) {
      for (size_t i = 0; i < instance.robot.bodies.size(); ++i)
        if (instance.robot.bodies[i].name == name) return first_body + static_cast<int>(i);
      return -1;
    };
    const int first_joint = static_cast<int>(flat.joints.size());
    for (const Joint& j : instance.robot.joints)
      add_joint(j, static_cast<int>(r), first_body, body_index, instance.placement);
    auto joint_index = [&](const std::string& name) {
      for (size_t i = 0; i < instance.robot.joints.size(); ++i)
        if (instance.robot.joints[i].name == name) return first_joint + static_cast<int>(i);
      return -1;
    };
    for (const Sensor& s : instance.robot.sensors) {
      FlatSensor sensor;
      sensor.name = s.name;
      sensor.robot = static_cast<int>(r);
      sensor.source = &s;
      sensor.body = s.body.empty() ? -1 : body_index(s.body);
      sensor.joint = s.joint.empty() ? -1 : joint_index(s.joint);
      flat.sensors.push_back(sensor);
    }
    for (const Actuator& a : instance.robot.actuators) {
      FlatActuator actuator;
      actuator.name = a.name;
      actuator.robot = static_cast<int>(r);
      actuator.source = &a;
      actuator.joint = joint_index(a.joint);
      flat.actuators.push_back(actuator);
    }
  }
  return flat;
}

std::string QualifiedBodyName(const FlatModel& model, int body) {
  const FlatBody& b = model.bodies[static_cast<size_t>(body)];
  if (b.robot < 0) return b.name;
  return model.world->robots[static_cast<size_t>(b.robot)].name + "/" + b.name;
}

}  // namespace simpartner::model
