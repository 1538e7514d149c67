// The loaded world flattened into the indexed lists the simulation and the
// bus use: world objects first, then each robot's bodies, all in the world
// frame at step 0. SIM_MODEL and SIM_STATE index these lists.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "simpartner/model/model.h"

namespace simpartner::model {

struct FlatBody {
  std::string name;
  int robot = -1;                         // index into world.robots, -1 = world object
  const Body* source = nullptr;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // body frame in the world
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // world frame
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // world frame
};

struct FlatJoint {
  std::string name;
  int robot = -1;
  const Joint* source = nullptr;
  int body1 = -1;                         // flat body index, -1 = static world
  int body2 = -1;
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // world frame
  Eigen::Vector3d axis[2];                // world frame
  // The original's commands address three slots x, y, z; a joint axis takes
  // the slot of the robot axis it is most aligned with (a wheel axle along
  // z takes slot 3, as in "1000,1000,100,0,0,0.2").
  int slot[2] = {0, 1};
  int num_axes = 0;
};

struct FlatSensor {
  std::string name;
  int robot = -1;
  const Sensor* source = nullptr;
  int body = -1;
  int joint = -1;
};

struct FlatActuator {
  std::string name;
  int robot = -1;
  const Actuator* source = nullptr;
  int joint = -1;
};

struct FlatModel {
  const World* world = nullptr;
  std::vector<FlatBody> bodies;
  std::vector<FlatJoint> joints;
  std::vector<FlatSensor> sensors;
  std::vector<FlatActuator> actuators;

  // Lookups by robot instance name ("" = any robot) and element name; -1
  // when absent.
  int FindActuator(const std::string& robot, const std::string& name) const;
  int FindSensor(const std::string& robot, const std::string& name) const;
  int FindBody(const std::string& robot, const std::string& name) const;
  int FindJoint(const std::string& robot, const std::string& name) const;
  int FindActuatorByPort(int port) const;
  int FindSensorByPort(int port) const;
};

// world must outlive the result (it points into it).
FlatModel Flatten(const World& world);

// A body's name for messages: "robot/body", or "body" for a world object.
std::string QualifiedBodyName(const FlatModel& model, int body);

}  // namespace simpartner::model
