// Keeps what the camera follows in view: a follow camera whose line of
// sight passes through a wall (the maze's, a pole task's cube) is drawn
// from in front of the wall instead, as game follow cameras do. The user's
// camera (its distance) is left as set, so the view goes back out when the
// robot leaves the wall behind. No GL here: unit tested on plain models.
#pragma once

#include <Eigen/Geometry>

#include <optional>

#include "simpartner/viewer/camera.h"
#include "simpartner/viewer/scene.h"

namespace simpartner::viewer {

// Distance along the ray from `from` in unit direction `direction` to the
// first static world object (a wall, a pillar: fixed, of no robot) it
// enters, if one is within max_distance. One the ray starts inside does
// not count. Boxes and spheres exactly, cylinders and capsules as their
// bounding boxes; objects that move (a pole the robot carries), the ground
// plane and the heightfield are left out.
std::optional<double> FirstWorldObjectHit(const Scene& scene, const Eigen::Vector3d& from,
                                          const Eigen::Vector3d& direction, double max_distance);

// The camera to draw while following: `camera`, moved in along its line of
// sight to just before the first world object between its target and its
// eye, and never closer than kMinClearDistance.
Camera UnblockedCamera(const Camera& camera, const Scene& scene);
inline constexpr double kMinClearDistance = 0.3;  // [m]
inline constexpr double kWallClearance = 0.15;    // [m] eye to the blocking surface

}  // namespace simpartner::viewer
