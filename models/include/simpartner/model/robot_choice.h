// simpartner-sim --robot: a shipped robot by its short name (gen1 ...
// gen4) or a robot file, put into the loaded world at a pose, replacing
// the world's robots or beside them.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/model/model.h"

namespace simpartner::model {

struct ShippedRobot {
  const char* name;  // what --robot takes
  const char* file;  // under models/robots/
};
// gen1, gen1-light, gen2, gen3, gen4.
const std::vector<ShippedRobot>& ShippedRobots();

struct RobotChoice {
  std::string robot;  // a ShippedRobots() name, or a robot file (found as data)
  // Position [m] in world coordinates and yaw [rad] about the world's up
  // axis; unset: where the world's first robot stands, else the origin (the
  // robot files put their origin on the ground).
  std::optional<Eigen::Vector3d> position;
  double yaw = 0.0;
  bool add = false;  // beside the world's robots instead of replacing them
};

// Reads "x,y,z" or "x,y,z,yaw_deg" (the value of --robot-pose) into
// choice. Throws ConfigError naming the flag and the value.
void ParseRobotPose(const std::string& text, RobotChoice* choice);

// The robot file of choice.robot: a shipped name's file, else the name
// found as a data file (FindRobotFile). Throws ConfigError with a "did you
// mean" for a name that is neither.
std::string RobotFileOf(const std::string& robot);

// Loads the chosen robot and puts it into world (see RobotChoice). The
// instance keeps the name of the robot it replaces ("WorkPartner" in the
// shipped worlds, so sequences still address it); an added one gets that
// name with a number. Throws ModelError (the robot file's problems) or
// ConfigError (placement out of range, a port or material clash).
void PlaceRobot(const RobotChoice& choice, World* world);

}  // namespace simpartner::model
