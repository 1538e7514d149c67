// From a world's local frame to the Earth (WGS-84), for GNSS readings: the
// exact ENU -> ECEF -> geodetic conversion, not a flat-earth one, so that a
// robot kilometres from the origin still reads the right latitude.
#pragma once

#include <Eigen/Core>

#include "simpartner/model/model.h"

namespace simpartner::sim {

// East, north and up unit vectors of a world, in world coordinates: east
// is the world's x axis made perpendicular to up (its z axis when x is
// nearly up), north = up x east. In the y-up worlds of the original: east
// = +x, north = -z, up = +y.
struct LocalFrame {
  Eigen::Vector3d east, north, up;
};
LocalFrame LocalFrameOf(const Eigen::Vector3d& up);

// Latitude, longitude [deg] and altitude above the ellipsoid [m] of the
// point `enu` [m] (east, north, up) from origin.
Eigen::Vector3d EnuToGeodetic(const model::GeodeticOrigin& origin, const Eigen::Vector3d& enu);

}  // namespace simpartner::sim
