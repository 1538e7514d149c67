#include "simpartner/sim/geodetic.h"

#include <cmath>

namespace simpartner::sim {
namespace {

constexpr double kSemiMajorAxis = 6378137.0;                  // [m] WGS-84 a
constexpr double kFlattening = 1.0 / 298.257223563;           // WGS-84 f
constexpr double kEccentricity2 = kFlattening * (2.0 - kFlattening);
constexpr double kDegree = M_PI / 180.0;

// Prime-vertical radius of curvature at latitude phi [rad].
double PrimeVerticalRadius(double phi) {
  const double s = std::sin(phi);
  return kSemiMajorAxis / std::sqrt(1.0 - kEccentricity2 * s * s);
}

}  // namespace

LocalFrame LocalFrameOf(const Eigen::Vector3d& up) {
  const Eigen::Vector3d u = up.normalized();
  const Eigen::Vector3d reference =
      std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d east = (reference - reference.dot(u) * u).normalized();
  return LocalFrame{east, u.cross(east), u};
}

Eigen::Vector3d EnuToGeodetic(const model::GeodeticOrigin& origin, const Eigen::Vector3d& enu) {
  const double phi0 = origin.latitude * kDegree, lambda0 = origin.longitude * kDegree;
  const double sp = std::sin(phi0), cp = std::cos(phi0);
  const double sl = std::sin(lambda0), cl = std::cos(lambda0);
  // The origin and the point in Earth-centred, Earth-fixed coordinates.
  const double n0 = PrimeVerticalRadius(phi0);
  const double e = enu.x(), n = enu.y(), u = enu.z();
  const double x = (n0 + origin.altitude) * cp * cl - sl * e - sp * cl * n + cp * cl * u;
  const double y = (n0 + origin.altitude) * cp * sl + cl * e - sp * sl * n + cp * sl * u;
  const double z = (n0 * (1.0 - kEccentricity2) + origin.altitude) * sp + cp * n + sp * u;
  // Back to geodetic by fixed-point iteration on the latitude: each
  // round gains about three digits near the surface; six reach 1e-12 rad.
  const double p = std::hypot(x, y);
  double phi = std::atan2(z, p * (1.0 - kEccentricity2));
  double h = 0.0;
  for (int k = 0; k < 6; ++k) {
    const double radius = PrimeVerticalRadius(phi);
    h = p / std::cos(phi) - radius;
    phi = std::atan2(z, p * (1.0 - kEccentricity2 * radius / (radius + h)));
  }
  h = p / std::cos(phi) - PrimeVerticalRadius(phi);
  return Eigen::Vector3d(phi / kDegree, std::atan2(y, x) / kDegree, h);
}

}  // namespace simpartner::sim
