// The MJCF the MuJoCo engine loads from memory: our world as it is, y up
// (MuJoCo takes any gravity), bodies nested as the body tree hangs them,
// named by flat index (b<i>, j<i>_<axis>, g<i>, a<i>_<axis>) so that the
// engine finds them again. Contact and motor settings here are only
// placeholders: the engine sets them per contact and per step.
// (simpartner-convert writes MJCF for people, z up, in convert/.)
#pragma once

#include <string>

#include "simpartner/model/body_tree.h"
#include "simpartner/parameters.h"

namespace simpartner::sim {

inline constexpr const char* kMjcfPlane = "plane";
inline constexpr const char* kMjcfField = "field";
std::string MjcfBodyName(int body);
std::string MjcfGeomName(int body);
std::string MjcfJointName(int joint, int axis);
std::string MjcfActuatorName(int joint, int axis);

std::string EngineMjcf(const model::FlatModel& model, const model::BodyTree& tree,
                       const Parameters& params);

}  // namespace simpartner::sim
