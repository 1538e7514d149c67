#include "ode_soil.h"

#include "ode_convert.h"

#include <algorithm>
#include <cmath>

namespace simpartner::sim {
namespace {

// Points along the loaded arc (soil_mechanics.h).
constexpr int kArcSamples = 64;
// The least stiffness [N/m] the normal row gets (at first touch Bekker's
// is 0: the CFM would be infinite).
constexpr double kLeastStiffness = 1.0;
// The most compliance [m/(N s)] a friction row gets where the shear's
// slope is flat.
constexpr double kMostSlip = 1.0;

// A friction row's compliance [m/(N s)] for a shear force of slope
// `slope` [N s/m] against the row's velocity: ODE's slip, -1 / slope,
// at most kMostSlip where the slope is flat.
double Compliance(double slope) { return slope < -1.0 / kMostSlip ? -1.0 / slope : kMostSlip; }

// A unit vector along the surface: the memory's first coordinate.
Eigen::Vector3d AlongSurface(const Eigen::Vector3d& up) {
  const Eigen::Vector3d seed =
      std::abs(up.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  return (seed - seed.dot(up) * up).normalized();
}

}  // namespace

void OdeSoil::AddGround(dGeomID plane, const model::SoilParameters& soil) {
  dVector4 p;
  dGeomPlaneGetParams(plane, p);
  Ground ground{Soil::From(soil), SoilSurface{}, SoilMemory{soil.n}};
  ground.surface.up = Eigen::Vector3d(p[0], p[1], p[2]).normalized();
  ground.surface.origin = ground.surface.up * p[3];
  ground.surface.u_axis = AlongSurface(ground.surface.up);
  grounds_.emplace(plane, std::move(ground));
}

void OdeSoil::AddHeightfield(dGeomID field, const model::SoilParameters& soil,
                             const model::Heightfield& shape, const Eigen::Isometry3d& pose) {
  Ground ground{Soil::From(soil), SoilSurface{}, SoilMemory{soil.n}, &shape, pose};
  grounds_.emplace(field, std::move(ground));
}

SoilSurface OdeSoil::SurfaceUnder(const Ground& ground, const WheelState& wheel) {
  if (ground.shape == nullptr) return ground.surface;
  const model::Heightfield& h = *ground.shape;
  // In the field's frame (y up): the lowest rim point for the field's up,
  // then again for the normal found there.
  const Eigen::Isometry3d to_field = ground.pose.inverse();
  const Eigen::Vector3d centre = to_field * wheel.centre;
  const Eigen::Vector3d axle = to_field.linear() * wheel.axle;
  // Slopes of the interpolated surface by differences over a quarter cell
  // each way, inside the field (its heights are clamped at the border).
  auto slope = [](double at, double cell, double half_extent, const auto& height) {
    const double lo = std::clamp(at - 0.25 * cell, -half_extent, half_extent);
    const double hi = std::clamp(at + 0.25 * cell, -half_extent, half_extent);
    return hi > lo ? (height(hi) - height(lo)) / (hi - lo) : 0.0;
  };
  const double dx = h.width / std::max(1, h.columns - 1), dz = h.depth / std::max(1, h.rows - 1);
  Eigen::Vector3d up = Eigen::Vector3d::UnitY(), lowest = centre;
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::Vector3d in_plane = up - up.dot(axle) * axle;
    if (in_plane.norm() < 1e-6) break;  // axle upright: no lowest point
    lowest = centre - wheel.radius * in_plane.normalized();
    const double x = lowest.x(), z = lowest.z();
    const double slope_x = slope(x, dx, 0.5 * h.width, [&](double u) { return h.HeightAt(u, z); });
    const double slope_z = slope(z, dz, 0.5 * h.depth, [&](double w) { return h.HeightAt(x, w); });
    up = Eigen::Vector3d(-slope_x, 1.0, -slope_z).normalized();
  }
  SoilSurface surface;
  surface.origin = ground.pose * Eigen::Vector3d(lowest.x(), h.HeightAt(lowest.x(), lowest.z()),
                                                 lowest.z());
  surface.up = ground.pose.linear() * up;
  surface.u_axis = AlongSurface(surface.up);
  surface.keyed_apart = true;
  surface.key_origin = ground.pose.translation();
  surface.key_u = ground.pose.linear() * Eigen::Vector3d::UnitX();
  surface.key_w = ground.pose.linear() * Eigen::Vector3d::UnitZ();
  return surface;
}

WheelState OdeSoil::StateOf(dGeomID wheel, dBodyID body) const {
  WheelState state;
  dReal radius = 0, length = 0;
  dGeomCylinderGetParams(wheel, &radius, &length);
  state.radius = radius;
  state.width = length;
  state.centre = FromOde(dGeomGetPosition(wheel));
  const dReal* r = dGeomGetRotation(wheel);  // 3 x 4, row-major: column 2 is the axis
  state.axle = Eigen::Vector3d(r[2], r[6], r[10]).normalized();
  dVector3 velocity;
  dBodyGetPointVel(body, state.centre.x(), state.centre.y(), state.centre.z(), velocity);
  state.velocity = FromOde(velocity);
  state.angular_velocity = FromOde(dBodyGetAngularVel(body));
  return state;
}

bool OdeSoil::Contact(dGeomID wheel, dBodyID body, dGeomID ground_geom, WheelContact* out) {
  if (dGeomGetClass(wheel) != dCylinderClass) return false;
  Ground& ground = grounds_.at(ground_geom);
  const WheelState state = StateOf(wheel, body);
  const SoilSurface surface = SurfaceUnder(ground, state);
  WheelSoilSlopes slopes;
  // The soil keeps this state's rut as it answers it.
  const WheelSoilForces now =
      PressWheelOnSoil(ground.soil, state, surface, &ground.memory, kArcSamples, &slopes);
  if (!now.touching) return true;
  const Eigen::Vector3d up = surface.up;
  const Eigen::Vector3d in_plane = up - up.dot(state.axle) * state.axle;
  const Eigen::Vector3d wheel_up = in_plane.normalized();
  const Eigen::Vector3d forward = wheel_up.cross(state.axle).normalized();
  const SoilGround kind = ground.shape != nullptr ? SoilGround::kHeightfield : SoilGround::kPlane;
  pressing_.push_back(Pressed{wheel, now, surface, forward, state.axle,
                              state.centre - state.radius * wheel_up, state.width, kind});

  // Normal: the soil's stiffness against sinking further.
  const double stiffness = std::max(kLeastStiffness, slopes.stiffness);
  // First friction row: the shear's force along forward against the slip
  // velocity v of the lowest rim point, and its slope.
  const double slip_velocity = now.forward_speed - state.radius * now.spin;
  const double thrust = now.shear_force.dot(forward);
  const double slip1 = Compliance(slopes.thrust_slope);
  // Second, across (ODE's second direction, normal x fdir1): the shear's
  // side force against the wheel's speed along it, and its slope.
  const Eigen::Vector3d across = up.cross(forward);
  const double side_velocity = state.velocity.dot(across);
  const double side_force = now.side_force * state.axle.dot(across);
  const double slip2 = Compliance(slopes.side_slope);

  dContact contact{};
  contact.geom.g1 = wheel;
  contact.geom.g2 = ground_geom;
  ToOdeVector(state.centre - state.radius * wheel_up, contact.geom.pos);
  ToOdeVector(up, contact.geom.normal);
  // ODE caps a contact's push-out velocity (contactMaxCorrectingVel), so
  // the soil's force itself is a plain force; the row adds, implicitly,
  // what further sinking in this step adds to it: depth 0 (no push-out)
  // and CFM 1 / (h k) make it k times the step's sinking.
  contact.geom.depth = 0.0;
  // Without dContactApprox1 ODE's mu and mu2 are force bounds [N]: the
  // soil's shear strength over the loaded arc, whatever the row's force.
  contact.surface.mode = dContactSoftERP | dContactSoftCFM | dContactFDir1 | dContactMu2 |
                         dContactSlip1 | dContactSlip2 | dContactMotion1 | dContactMotion2;
  contact.surface.mu = now.shear_strength;
  contact.surface.mu2 = now.shear_strength;
  contact.surface.soft_erp = 0.0;
  contact.surface.soft_cfm = 1.0 / (params_.stepsize * stiffness);
  contact.surface.slip1 = slip1;
  contact.surface.motion1 = slip_velocity + slip1 * thrust;
  contact.surface.slip2 = slip2;
  contact.surface.motion2 = side_velocity + slip2 * side_force;
  ToOdeVector(forward, contact.fdir1);
  out->contact = contact;

  // Through the centre: the normal stresses and the shear's part along up.
  out->force = now.normal_force + now.shear_force.dot(up) * up;
  // The shear's torque about the axle beyond the row's r T at the rim.
  out->torque = (now.shear_torque - state.radius * thrust) * state.axle;
  return true;
}

void OdeSoil::AfterStep() {
  last_step_.swap(pressing_);
  pressing_.clear();
}

}  // namespace simpartner::sim
