// Wheels on soft soil, for any engine (docs/soil.md): the soil's answer
// to a wheel this step as rows an engine solves implicitly with the rest
// of its step. soil_mechanics.h gives the stresses; this unit turns them
// into what an engine needs, the same for ODE (ode_soil.h) and MuJoCo
// (mujoco_soil.cpp), so that both meet one soil:
//   - a plain force and torque, the soil's answer at this state (an
//     engine caps a contact's push-out velocity, so a row cannot carry
//     it);
//   - a normal row: what sinking further within the step adds, the
//     stiffness k = dF/dz times that sinking (backward in time while the
//     wheel sinks);
//   - a row along the rolling direction: the soil's shear force as a
//     function of the slip velocity v of the rim's lowest point,
//     linearized there: T(v) = thrust + thrust_slope (v - slip_velocity);
//   - a row across: the side force against the wheel's speed along its
//     axle, linearized the same way;
//   - both friction rows bounded by the soil's shear strength over the
//     loaded arc, as forces.
// The soil records how deep each wheel presses it as it answers it, so
// every state's rut stays (PressWheelOnSoil), and what each wheel met
// becomes the step's readout (engine.h: WheelSoilReadout).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simpartner/model/model.h"
#include "simpartner/sim/engine.h"
#include "simpartner/sim/soil_mechanics.h"
#include "soil_plate.h"

namespace simpartner::sim {

// One wheel's (or plate's) rows against one soil this step, in world
// coordinates.
struct SoilContactRows {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // where `force` acts (a wheel's centre)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // where the rows act (the rim's lowest point)
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();     // the soil surface's normal
  Eigen::Vector3d forward = Eigen::Vector3d::UnitX();  // the rolling direction
  Eigen::Vector3d across = Eigen::Vector3d::UnitZ();   // up x forward
  // The soil's answer at this state, less what the friction rows carry:
  // a force through the centre and a torque.
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  double stiffness = 0.0;  // [N/m] of the normal row, >= kLeastSoilStiffness
  // Along forward: the slip velocity [m/s] now, the shear's force [N]
  // there and its slope [N s/m] (<= 0: the force resists the slip).
  double slip_velocity = 0.0, thrust = 0.0, thrust_slope = 0.0;
  // Across: the wheel's speed [m/s] along it, the side force [N] and its
  // slope [N s/m].
  double side_velocity = 0.0, side_force = 0.0, side_slope = 0.0;
  double shear_strength = 0.0;  // [N] the bound of each friction row
  // A wheel's readout of this step (SoilContacts::RowForce), -1 for a plate.
  int readout = -1;

  // The row's force [N] along forward at slip velocity v.
  double ThrustAt(double v) const { return thrust + thrust_slope * (v - slip_velocity); }
  double SideForceAt(double v) const { return side_force + side_slope * (v - side_velocity); }
};

// The least stiffness [N/m] a normal row gets: at first touch Bekker's
// slope is 0, and an engine's compliance 1 / (h k) would be infinite.
inline constexpr double kLeastSoilStiffness = 1.0;
// The least steepness [N s/m] of a friction row's slope where the shear
// is flat (saturated), so that its compliance stays finite.
inline constexpr double kLeastShearSlope = 1.0;
// A plate (soil_plate.h) held by the soil's shear creeps at most this
// fast [m/s] below its strength: its rows' slope is the strength over it.
inline constexpr double kPlateCreepSpeed = 1e-3;
// A wheel whose rim and centre both move slower than this [m/s] (the
// mean of this step and the last: WheelHistory) is at rest: the soil holds it by its shear displacement from where it came to
// rest (an anchor), Janosi and Hanamoto's tau_max (1 - e^(-j / K)) for a
// small j, a spring of strength / K, not by the slip law, which has no
// rest (at any speed it would let the wheel creep). Past K from the
// anchor, or moving faster, it slides by the slip law again.
inline constexpr double kRestSpeed = 1e-3;
// A wheel is stuck when sunk to its axle (soil_mechanics.h), or when it
// has been driven with slip kStuckSlip or more for kStuckSeconds.
inline constexpr double kStuckSlip = 0.95;
inline constexpr double kStuckSeconds = 1.0;
// The most cells a ground's memory keeps (about 120 MB; at 0.5 mm cells
// 1 km of one wheel's track, 250 m of gen3's four); past it the cells
// pressed longest ago go, and a wheel back on them meets untouched soil.
inline constexpr size_t kMaxSoilCells = 2000000;

// The soil grounds of a world and what the wheels on them did.
class SoilContacts {
 public:
  explicit SoilContacts(double stepsize) : stepsize_(stepsize) {}

  // A ground plane of soil, a x + b y + c z = d (`plane`, as the model
  // gives it; (a, b, c) need not be unit). Returns its index.
  int AddPlane(const Eigen::Vector4d& plane, const model::SoilParameters& soil);
  // A heightfield of soil: `shape` (kept by the caller) placed at `pose`
  // (its frame y-up). Each wheel meets the tangent plane of the field
  // under its lowest point. Returns its index.
  int AddHeightfield(const model::SoilParameters& soil, const model::Heightfield& shape,
                     const Eigen::Isometry3d& pose);
  int grounds() const { return static_cast<int>(grounds_.size()); }

  // The rows of `wheel` (flat body `body`) on ground `ground` this step,
  // none when the wheel is above it. The soil records the rut.
  std::optional<SoilContactRows> Contact(int ground, int body, const WheelState& wheel);
  // The rows of a body that is not a wheel (a box, sphere or capsule) on
  // ground `ground`: Bekker's plate (soil_plate.h), its normal row at the
  // pressure's centroid, its friction rows holding it with the soil's
  // shear (creeping below kPlateCreepSpeed); none when it is above.
  std::optional<SoilContactRows> PlateContact(int ground, const PlateState& plate);

  // The force [N] the rows of `rows.readout` carried in the step (at
  // rows.point), as the engine solved it: the wheel's readout then tells
  // the force the step applied, plain and rows, not the evaluation before
  // the solve. Call it for every wheel's rows, before AfterStep.
  void RowForce(const SoilContactRows& rows, const Eigen::Vector3d& force);

  // Ends a step: the wheels that touched soil in it become LastStep(),
  // and each ground's memory is kept within kMaxSoilCells, saying so in
  // `messages` when it forgets.
  void AfterStep(std::vector<std::string>* messages);
  // The wheels that pressed soil in the last step (a wheel near a plane
  // and a field of soil is evaluated on each: only the one it presses
  // counts).
  const std::vector<WheelSoilReadout>& LastStep() const { return last_step_; }

 private:
  struct Ground {
    Soil soil;
    SoilMemory memory;
    SoilSurface surface;                        // a plane's
    const model::Heightfield* shape = nullptr;  // a heightfield's
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  };
  // The surface `wheel` meets on `ground`: the plane, or the heightfield's
  // tangent plane under the wheel's lowest point.
  static SoilSurface SurfaceUnder(const Ground& ground, const WheelState& wheel);
  // The plane, or the heightfield's tangent plane below `point`.
  static SoilSurface SurfaceBelow(const Ground& ground, const Eigen::Vector3d& point);
  // The heightfield's tangent plane at (x, z) of its own frame.
  static SoilSurface FieldPlane(const Ground& ground, double x, double z);

  double stepsize_;
  std::vector<Ground> grounds_;
  std::vector<WheelSoilReadout> pressing_, last_step_;  // this step's, the last step's
  // Holds a wheel at rest by its anchor (kRestSpeed): its friction rows
  // become the shear's spring from where it came to rest, and its plain
  // force the normal stresses' `normal_force` alone. True when it holds it.
  struct WheelHistory;
  bool HoldAtRest(int ground, int body, const WheelState& wheel,
                  const Eigen::Vector3d& normal_force, WheelHistory* history,
                  SoilContactRows* rows);
  // Whether the wheel has been driven at slip kStuckSlip or more for
  // kStuckSeconds, counting this step at `slip`.
  bool SlippingLong(double slip, WheelHistory* history) const;

  // What a wheel on soil did in the steps before this one.
  struct WheelHistory {
    double slipping_seconds = 0.0;  // driven at kStuckSlip or more
    // Its velocities the step before (once it has one): rest is judged on
    // the mean of two steps, so that a wheel rocking at the step's period
    // (each step the opposite of the last, as the slip law's shear flips
    // sign at speeds near 0) counts as still, and its anchor stops it.
    bool has_velocity = false;
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), rim_velocity = Eigen::Vector3d::Zero();
    bool seen = false;  // this step
  };
  std::map<std::pair<int, int>, WheelHistory> history_;  // per (ground, wheel body)
  struct Anchor {
    Eigen::Vector3d at = Eigen::Vector3d::Zero();  // the lowest rim point when it came to rest
    bool seen = false;                             // this step
  };
  std::map<std::pair<int, int>, Anchor> anchors_;  // per (ground, wheel body) at rest
};

}  // namespace simpartner::sim
