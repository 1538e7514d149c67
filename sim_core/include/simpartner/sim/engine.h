// The physics engine behind a Simulation: what the controllers, sensors,
// health check and publishing need of it, and nothing of any engine's own
// types. Two implementations, each in sim_core/src with its engine's
// headers private to it: ODE (ode_world.h, the original's engine and the
// default) and MuJoCo (mujoco_world.h); MakeEngine builds either. The
// contact rules both apply live once, in contact_rules.h.
// docs/engines.md compares them.
//
// Frames are ours for both: the world frame of the files (y up for the
// original's worlds), body frames as in the robot files, joint values
// counted body1 relative to body2, every quantity after the last step.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/model/flat_model.h"
#include "simpartner/parameters.h"

namespace simpartner::sim {

// The engine stopped on an internal error or found a state it cannot
// integrate. The engine that raised it is dead: every further Step()
// throws again; a new engine (the sim's reset) works.
// what(): "<engine> failed: <its message> (during <what>); bodies: a, b".
class EngineError : public Error {
 public:
  EngineError(const std::string& engine, std::string engine_message, std::string during,
              std::vector<std::string> bodies);
  // The engine's own text.
  const std::string& engine_message() const { return engine_message_; }
  // "step", "collision", "building body 'Bot/Wheel1'", ...
  const std::string& during() const { return during_; }
  // Bodies (qualified "robot/body") the engine could not integrate: a
  // state that is non-finite or beyond the loader's ranges; empty when
  // none stands out.
  const std::vector<std::string>& bodies() const { return bodies_; }

 private:
  std::string engine_message_;
  std::string during_;
  std::vector<std::string> bodies_;
};

struct BodyReadout {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // body frame origin, world
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // of the body frame origin
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d contact_force = Eigen::Vector3d::Zero();     // sum over this step's contacts
  Eigen::Vector3d contact_torque = Eigen::Vector3d::Zero();    // about the centre of mass
};

struct JointReadout {
  double position[3] = {0, 0, 0};
  // position with rotational axes unwrapped: no jump at +-pi.
  double continuous_position[3] = {0, 0, 0};
  double rate[3] = {0, 0, 0};
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  // [m] between the anchor as body1 and as body2 hold it: how far the
  // constraint is from satisfied (0 where an engine's joints are exact in
  // joint coordinates, as MuJoCo's are).
  double anchor_error = 0.0;
  // What the joint applies to body1 and body2 (torques about each body's
  // centre of mass); zero on the static world's side.
  Eigen::Vector3d force1 = Eigen::Vector3d::Zero(), torque1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d force2 = Eigen::Vector3d::Zero(), torque2 = Eigen::Vector3d::Zero();
};

// One contact point of the last step as the engine set it up.
struct ContactReadout {
  int body1 = -1, body2 = -1;  // flat bodies; -1 = the ground or a static object
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    // unit, world
  // The rolling direction the contact rules gave it (unit, its sign
  // arbitrary: friction acts along a line), zero when it has none.
  Eigen::Vector3d rolling_direction = Eigen::Vector3d::Zero();
};

// The soil grounds of a world: at most one of each.
enum class SoilGround { kPlane, kHeightfield };

// A wheel on soft soil in the last step (docs/soil.md): the soil model's
// figures at the state the step began with, which gave the step's forces.
struct WheelSoilReadout {
  int body = -1;         // the wheel's flat body (a body has one geom)
  SoilGround ground = SoilGround::kPlane;  // the soil it pressed
  double sinkage = 0.0;  // [m] lowest rim point below the untouched surface
  double slip = 0.0;     // [-] 1 - v / (r omega) driving, r omega / v - 1 braking
  Eigen::Vector3d normal_force = Eigen::Vector3d::Zero();  // [N] world frame
  Eigen::Vector3d shear_force = Eigen::Vector3d::Zero();   // [N] world frame
  Eigen::Vector3d forward = Eigen::Vector3d::Zero();  // rolling direction (unit)
  Eigen::Vector3d axle = Eigen::Vector3d::Zero();     // unit
  Eigen::Vector3d lowest_point = Eigen::Vector3d::Zero();  // of the rim, world
  double width = 0.0;  // [m] of the tread
  // The soil's untouched surface: a point of it, its normal and the
  // direction of its rut grid's first axis (unit, along it).
  Eigen::Vector3d surface_origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  Eigen::Vector3d surface_u_axis = Eigen::Vector3d::Zero();
  double axle_torque = 0.0;  // [N m] of the shear about the axle, positive against the spin
  bool stuck = false;
};

class PhysicsEngine {
 public:
  virtual ~PhysicsEngine() = default;

  // "ode" or "mujoco", as the engine parameter names it.
  virtual const char* name() const = 0;

  // One step of params.stepsize. Throws EngineError when the engine fails;
  // it is dead from then on.
  virtual void Step() = 0;
  virtual bool dead() const = 0;
  // Messages the engine printed during the last Step (the first Step's
  // include those of the construction).
  virtual const std::vector<std::string>& last_messages() const = 0;
  virtual int last_contact_count() const = 0;

  virtual BodyReadout ReadBody(int body) const = 0;
  virtual JointReadout ReadJoint(int joint) const = 0;
  virtual double JointPosition(int joint, int axis) const = 0;
  virtual double JointRate(int joint, int axis) const = 0;
  // The wheels that pressed soil in the last step; none on rigid ground
  // and on an engine without soil.
  virtual std::vector<WheelSoilReadout> ReadWheelSoil() const { return {}; }
  // The contact points of the last step (tests compare the engines' rules
  // with them; a debugging view could draw them).
  virtual std::vector<ContactReadout> ReadContacts() const = 0;

  // Stops every body where it is: all velocities 0 (after a settle).
  virtual void ZeroVelocities() = 0;
  // Adds a force [N] at the centre of mass for the coming step only.
  virtual void AddForce(int body, const Eigen::Vector3d& force) = 0;
  // Velocity motor of one joint axis: drives the axis to `velocity` with
  // at most `max_force` [N or N m] (0 = no motor), until set again.
  virtual void SetMotor(int joint, int axis, double velocity, double max_force) = 0;
  // Joint stops of one axis; an infinite bound is no stop.
  virtual void SetStops(int joint, int axis, double lo, double hi) = 0;

  // Distance along the ray to the first geometry hit (range when nothing
  // is hit); geometry of exclude_body is ignored (the scanner's housing).
  virtual double CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         double range, int exclude_body) = 0;

  // The engine's own step on this built world with the motors as set and
  // none of our contact rules: the "bare" baseline of bench/sim_bench.
  // Leaves the readouts of Step undefined; for benchmarks only.
  virtual void BareStep() = 0;
};

// Sets the stops the files give each joint axis (infinite: none) on a
// newly built engine: both engines' constructors end with it.
void SetStopsOfTheFiles(const model::FlatModel& model, PhysicsEngine* engine);

// The engine params.engine names, built from model (which, and its World,
// must outlive it). Throws EngineError when the engine refuses a part.
std::unique_ptr<PhysicsEngine> MakeEngine(const model::FlatModel& model,
                                          const Parameters& params);

// What of model params.engine cannot represent, one line each naming the
// element, its file and line, and why (empty when all of it can). ODE
// represents everything the loader accepts; MuJoCo all but a loop of
// bodies.
std::vector<Diagnostic> EngineLimits(const model::FlatModel& model, const Parameters& params);

// The parameters params.engine does not read that differ from their
// defaults, as "key=value" (ODE's stepper settings under MuJoCo), so that
// a setting the run ignores is said, not silently dropped.
std::vector<std::string> ParametersTheEngineIgnores(const Parameters& params);

}  // namespace simpartner::sim
