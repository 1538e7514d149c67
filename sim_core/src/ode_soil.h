// Wheels on soft soil inside ODE's step (docs/soil.md): ODE's terms for
// the engine-neutral rows of soil_contact.h. For a wheel (a cylinder
// geom) on a ground plane or heightfield of soil, one contact joint and
// no rigid contact:
//   - the soil's force at this sinkage is a plain force of the step (ODE
//     caps a contact's push-out velocity, so a row cannot carry it);
//   - the normal row adds what sinking further in the step adds, k times
//     that sinking: depth 0, CFM 1 / (h k);
//   - the friction row along the rolling direction is the linearized
//     shear T(v) = T0 + T' (v - v0): ODE's motion1 = v0 + s T0 with slip1
//     s = -1 / T'; across (ODE's second direction, normal x fdir1), the
//     side force the same way (motion2, slip2); both bounded by the
//     soil's shear strength as forces (no dContactApprox1), as the row's
//     normal force is only the step's increment.
#pragma once

#include <ode/ode.h>

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/parameters.h"
#include "simpartner/sim/engine.h"
#include "soil_contact.h"

namespace simpartner::sim {

class OdeSoil {
 public:
  explicit OdeSoil(const Parameters& params) : params_(params), contacts_(params.stepsize) {}

  // A ground plane of soil.
  void AddGround(dGeomID plane, const model::SoilParameters& soil);
  // A heightfield of soil: `field` placed at `pose` (its frame y-up, as
  // ODE's), heights from `shape` (kept by the caller).
  void AddHeightfield(dGeomID field, const model::SoilParameters& soil,
                      const model::Heightfield& shape, const Eigen::Isometry3d& pose);
  bool IsGround(dGeomID geom) const { return grounds_.count(geom) > 0; }

  // The contact of `geom` (of body `body`, flat body `flat_body`) with
  // soil `ground` this step: a wheel's (a cylinder) or a plate's (a box,
  // sphere or capsule: soil_plate.h); nothing when it is above the soil.
  // False for any other geom (the caller collides it as rigid ground).
  struct BodyContact {
    std::optional<dContact> contact;       // to create and attach (body, 0)
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   // add at `at`
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // add to the body
    SoilContactRows rows;  // for RowForce once the step has solved them
  };
  bool Contact(dGeomID geom, dBodyID body, int flat_body, dGeomID ground, BodyContact* out);

  // What a contact's rows carried in the step (SoilContacts::RowForce).
  void RowForce(const SoilContactRows& rows, const Eigen::Vector3d& force) {
    contacts_.RowForce(rows, force);
  }
  // Ends a step (SoilContacts::AfterStep).
  void AfterStep(std::vector<std::string>* messages) { contacts_.AfterStep(messages); }
  const std::vector<WheelSoilReadout>& LastStep() const { return contacts_.LastStep(); }

 private:
  WheelState StateOf(dGeomID wheel, dBodyID body) const;
  // A box, sphere or capsule geom as a plate; none for another class.
  static std::optional<PlateState> PlateOf(dGeomID geom, dBodyID body);

  const Parameters& params_;
  SoilContacts contacts_;
  std::unordered_map<dGeomID, int> grounds_;  // geom -> SoilContacts' ground
};

}  // namespace simpartner::sim
