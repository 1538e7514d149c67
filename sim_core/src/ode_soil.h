// Wheels on soft soil inside ODE's step (docs/soil.md): for a
// wheel (a cylinder geom) on a ground plane or heightfield of soil (under
// the wheel: its tangent plane there), one contact joint
// whose rows carry the soil's force of this state, linearized so that
// ODE solves it implicitly with the rest of the step, and no rigid
// contact. soil_mechanics.h gives the stresses; this file turns them into
// ODE's terms:
//   - the soil's force F at this sinkage is a plain force of the step (ODE
//     caps a contact's push-out velocity, so a row cannot carry it), and
//     the normal row adds what sinking further in the step adds, k times
//     that sinking (depth 0, CFM 1 / (h k), k = dF/dz): backward in time
//     while the wheel sinks;
//   - the first friction row, along the wheel's rolling direction, is the
//     soil's shear force as a function of the slip velocity v of the rim's
//     lowest point, linearized there: T(v) = T0 + T' (v - v0) is ODE's
//     row with motion1 = v0 + s T0 and slip1 s = -1 / T';
//   - the second, across, is the soil's side force as a function of the
//     wheel's speed along its axle, linearized the same way (motion2,
//     slip2); both rows are bounded by the soil's shear strength over the
//     arc, as forces (no dContactApprox1), as the row's normal force is
//     only the step's increment;
//   - the shear's torque beyond what the row's force gives at the rim is
//     added as a torque.
// The soil records how deep each wheel presses it as it answers it, so
// every state's rut stays (soil_mechanics.h: PressWheelOnSoil).
#pragma once

#include <ode/ode.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>
#include <unordered_map>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/parameters.h"
#include "simpartner/sim/engine.h"
#include "simpartner/sim/soil_mechanics.h"

namespace simpartner::sim {

class OdeSoil {
 public:
  explicit OdeSoil(const Parameters& params) : params_(params) {}

  // A ground plane of soil.
  void AddGround(dGeomID plane, const model::SoilParameters& soil);
  // A heightfield of soil: `field` placed at `pose` (its frame y-up, as
  // ODE's), heights from `shape` (kept by the caller). Each wheel meets
  // the tangent plane of the field under its lowest point.
  void AddHeightfield(dGeomID field, const model::SoilParameters& soil,
                      const model::Heightfield& shape, const Eigen::Isometry3d& pose);
  bool IsGround(dGeomID geom) const { return grounds_.count(geom) > 0; }

  // The contact of `wheel` (a geom of body `body`) with soil `ground`
  // this step: nothing when the wheel is above it; false when `wheel` is
  // not a cylinder (the soil model has only wheels: the caller collides it
  // as rigid ground).
  struct WheelContact {
    std::optional<dContact> contact;       // to create and attach (body, 0)
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   // add at the centre of mass
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // add to the body
  };
  bool Contact(dGeomID wheel, dBodyID body, dGeomID ground, WheelContact* out);

  // Ends a step: the wheels that touched soil in it become LastStep().
  void AfterStep();

  // The wheels that pressed soil in the last step, in what frame and with
  // what forces (a wheel near a plane and a field of soil is evaluated on
  // each: only the one it presses counts).
  struct Pressed {
    dGeomID wheel;
    WheelSoilForces forces;
    SoilSurface surface;         // of the soil it pressed (a heightfield's: under it)
    Eigen::Vector3d forward;     // the wheel's rolling direction
    Eigen::Vector3d axle;        // unit
    Eigen::Vector3d lowest;      // its lowest rim point
    double width;                // of its tread [m]
    SoilGround ground;           // which soil it pressed
  };
  const std::vector<Pressed>& LastStep() const { return last_step_; }

 private:
  struct Ground {
    Soil soil;
    SoilSurface surface;  // a plane's
    SoilMemory memory;
    const model::Heightfield* shape = nullptr;  // a heightfield's
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  };
  WheelState StateOf(dGeomID wheel, dBodyID body) const;
  // The surface `wheel` meets on `ground`: the plane, or the heightfield's
  // tangent plane under the wheel's lowest point.
  static SoilSurface SurfaceUnder(const Ground& ground, const WheelState& wheel);

  const Parameters& params_;
  std::unordered_map<dGeomID, Ground> grounds_;
  std::vector<Pressed> pressing_, last_step_;  // this step's touching wheels, the last step's
};

}  // namespace simpartner::sim
