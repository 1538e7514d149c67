// Joint angles made continuous: ODE's hinge angle wraps at +-pi, so a
// wheel's angle jumps by 2 pi every turn; unwrapped it grows on. For
// simulations logged before the sim published its continuous angle.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

// How many of a joint type's axes are rotations (the rest are metres or none).
int RotationalAxes(const std::string& type);
// Joint name -> RotationalAxes of its type, for a simulation's joints.
std::map<std::string, int> JointRotationalAxes(DbConnection* db, uint32_t simulation);

// One joint's angles, step after step: a jump of more than pi from the
// step before is a whole turn.
class AngleUnwrapper {
 public:
  // Unwraps angles[0..axes) in place.
  void Unwrap(double* angles, int axes);

 private:
  double previous_[3] = {0, 0, 0};  // the raw angles of the step before
  double offset_[3] = {0, 0, 0};    // the whole turns added
  bool seen_ = false;
};

}  // namespace simpartner::logger
