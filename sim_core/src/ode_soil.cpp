#include "ode_soil.h"

#include "ode_convert.h"

namespace simpartner::sim {

void OdeSoil::AddGround(dGeomID plane, const model::SoilParameters& soil) {
  dVector4 p;
  dGeomPlaneGetParams(plane, p);
  grounds_.emplace(plane, contacts_.AddPlane(Eigen::Vector4d(p[0], p[1], p[2], p[3]), soil));
}

void OdeSoil::AddHeightfield(dGeomID field, const model::SoilParameters& soil,
                             const model::Heightfield& shape, const Eigen::Isometry3d& pose) {
  grounds_.emplace(field, contacts_.AddHeightfield(soil, shape, pose));
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

std::optional<PlateState> OdeSoil::PlateOf(dGeomID geom, dBodyID body) {
  PlateState plate;
  switch (dGeomGetClass(geom)) {
    case dBoxClass: {
      dVector3 sides;
      dGeomBoxGetLengths(geom, sides);
      plate.kind = model::GeometryKind::kBox;
      plate.size = FromOde(sides);
      break;
    }
    case dSphereClass:
      plate.kind = model::GeometryKind::kSphere;
      plate.size.x() = dGeomSphereGetRadius(geom);
      break;
    case dCapsuleClass: {
      dReal radius = 0, length = 0;
      dGeomCapsuleGetParams(geom, &radius, &length);
      plate.kind = model::GeometryKind::kCapsule;
      plate.size = Eigen::Vector3d(radius, length, 0);
      break;
    }
    default: return std::nullopt;
  }
  plate.pose.translation() = FromOde(dGeomGetPosition(geom));
  plate.pose.linear() = FromOdeRotation(dGeomGetRotation(geom));
  dVector3 velocity;
  const Eigen::Vector3d& at = plate.pose.translation();
  dBodyGetPointVel(body, at.x(), at.y(), at.z(), velocity);
  plate.velocity = FromOde(velocity);
  plate.angular_velocity = FromOde(dBodyGetAngularVel(body));
  return plate;
}

bool OdeSoil::Contact(dGeomID geom, dBodyID body, int flat_body, dGeomID ground,
                      BodyContact* out) {
  std::optional<SoilContactRows> rows;
  if (dGeomGetClass(geom) == dCylinderClass) {
    rows = contacts_.Contact(grounds_.at(ground), flat_body, StateOf(geom, body));
  } else if (const std::optional<PlateState> plate = PlateOf(geom, body)) {
    rows = contacts_.PlateContact(grounds_.at(ground), *plate);
  } else {
    return false;
  }
  if (!rows) return true;

  dContact contact{};
  contact.geom.g1 = geom;
  contact.geom.g2 = ground;
  ToOdeVector(rows->point, contact.geom.pos);
  ToOdeVector(rows->up, contact.geom.normal);
  // ODE caps a contact's push-out velocity (contactMaxCorrectingVel), so
  // the soil's force itself is a plain force; the row adds, implicitly,
  // what further sinking in this step adds to it: depth 0 (no push-out)
  // and CFM 1 / (h k) make it k times the step's sinking.
  contact.geom.depth = 0.0;
  // Without dContactApprox1 ODE's mu and mu2 are force bounds [N]: the
  // soil's shear strength over the loaded arc, whatever the row's force.
  contact.surface.mode = dContactSoftERP | dContactSoftCFM | dContactFDir1 | dContactMu2 |
                         dContactSlip1 | dContactSlip2 | dContactMotion1 | dContactMotion2;
  contact.surface.mu = rows->shear_strength;
  contact.surface.mu2 = rows->shear_strength;
  contact.surface.soft_erp = 0.0;
  contact.surface.soft_cfm = 1.0 / (params_.stepsize * rows->stiffness);
  // A row's force is (motion - v) / slip: T(v) with slip -1 / T'.
  contact.surface.slip1 = -1.0 / rows->thrust_slope;
  contact.surface.motion1 = rows->slip_velocity + contact.surface.slip1 * rows->thrust;
  contact.surface.slip2 = -1.0 / rows->side_slope;
  contact.surface.motion2 = rows->side_velocity + contact.surface.slip2 * rows->side_force;
  ToOdeVector(rows->forward, contact.fdir1);
  out->contact = contact;
  out->force = rows->force;
  out->at = rows->centre;
  out->torque = rows->torque;
  out->rows = *rows;
  return true;
}

}  // namespace simpartner::sim
