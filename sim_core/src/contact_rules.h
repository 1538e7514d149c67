// The engine-neutral rules of contact both engines apply, once: when a
// contact has a slip direction, which way a wheel rolls, and which bodies
// an engine that failed could not integrate. An engine adapter translates
// its own contacts and states into these terms and back (ode_world.cpp,
// mujoco_contacts.cpp, mujoco_world.cpp); it keeps no copy of a rule.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/model/flat_model.h"
#include "simpartner/model/surface.h"

namespace simpartner::sim {

// [m/s] a slip at or below this has no direction: the contact counts as
// sticking (the direction of a smaller slip is noise).
inline constexpr double kSlipDirectionSpeed = 1e-4;

// |normal x spin axis| at or below this (a wheel within 0.6 degrees of
// lying flat) leaves a "rolling" contact without a rolling direction.
// ODE's value since rolling materials came (docs/contacts.md says 0.6
// degrees), the one the validation figures were made with; MuJoCo's copy
// had drifted to 1e-3, which no test or experiment relied on.
inline constexpr double kMinRollingSine = 0.01;

// The direction (unit) along the slip, none when it is at most
// kSlipDirectionSpeed. slip: the relative velocity in the contact plane.
std::optional<Eigen::Vector3d> SlipDirection(const Eigen::Vector3d& slip);

// The rolling direction (unit) of a contact of two geoms whose combined
// material asks for one: perpendicular to the normal and to the spin axis
// (world frame) of the one geom of the two that spins. None when the
// material does not ask, neither or both spin (two wheels have no common
// rolling direction), or the wheel lies flat (kMinRollingSine).
std::optional<Eigen::Vector3d> RollingDirection(
    const model::SurfaceProperties& combined, const Eigen::Vector3d& normal,
    const std::optional<Eigen::Vector3d>& spin_axis1,
    const std::optional<Eigen::Vector3d>& spin_axis2);

// A moving body's state as an engine holds it (world frame).
struct BodyState {
  int body = -1;  // flat body
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector4d orientation = Eigen::Vector4d(1, 0, 0, 0);  // quaternion w x y z
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
};

// The bodies (qualified names, in flat order) an engine cannot integrate:
// a state non-finite or beyond the loader's ranges (models/README.md,
// "Physical ranges"), or a mass outside them (only a world built past the
// loader has one; it breaks a solver even with a finite state). What
// EngineError::bodies() names.
std::vector<std::string> SuspectBodies(const model::FlatModel& model,
                                       const std::vector<BodyState>& moving);

}  // namespace simpartner::sim
