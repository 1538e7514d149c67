// A ray against a heightfield, as ODE's heightfield collides (the same
// cells and triangles), walking only the cells under the ray. ODE's own
// ray test takes every cell in the ray's bounding box: a 50 m lidar ray
// over the 441 x 21 test track took about 0.8 ms.
#pragma once

#include <Eigen/Geometry>

#include "simpartner/model/model.h"

namespace simpartner::sim {

// The distance along `direction` (unit) from `origin` to the first point
// of the field's surface within `range`, or `range` when the ray misses
// it; 0 when `origin` is below the surface. The field spans x in
// [-width/2, width/2] and z in [-depth/2, depth/2] of its frame (y up), the
// sample of column c and row r at height scale * sample + offset, each
// cell split along the diagonal from (c + 1, r) to (c, r + 1), as ODE's
// dxHeightfield. `pose` places the field's frame in the world.
double RayHeightfield(const model::Heightfield& field, const Eigen::Isometry3d& pose,
                      const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                      double range);

}  // namespace simpartner::sim
