// The ODE engine: ODE objects built from a model::FlatModel: bodies, geoms,
// joints, the collision space, plane and heightfield. One Step() is
// collide, step, empty the contact group (ODE's demo_buggy loop), with
// contact forces summed per body from joint feedback. Everything given to
// ODE was validated by the loader (models/README.md, "Physical ranges");
// what ODE still cannot integrate (a state that explodes within one step)
// ends in an OdeError, not abort(). Internal to sim_core: ODE's headers
// and types stay in its sim_core/src/ode_*.cpp files (engine.h is the
// public face, MakeEngine builds it).
#pragma once

#include <ode/ode.h>

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/sim/engine.h"
#include "simpartner/model/flat_model.h"
#include "simpartner/model/surface.h"
#include "simpartner/parameters.h"

namespace simpartner::sim {

// ODE stopped on an internal error or a failed assertion (dError, dDebug:
// ODE would abort() or exit() after its handler). The OdeWorld that raised
// it is dead: every further Step() throws again, and its ODE objects are
// abandoned, not freed (ODE left them mid-step: a locked space, a job list
// not emptied), some KB per body. A new OdeWorld (the sim's reset) works.
// what(): "ODE failed: <ODE's message> (during <what>); bodies: a, b".
class OdeError : public EngineError {
 public:
  OdeError(std::string ode_message, std::string during, std::vector<std::string> bodies);
  // ODE's own text, e.g. 'assertion "!bSafeNormalize4Fault" failed in
  // dxNormalize4() [odemath.h:53]'.
  const std::string& ode_message() const { return engine_message(); }
};

// Makes ODE's fatal errors (dError) and debug assertions (dDebug) throw
// OdeError and its messages (dMessage) warnings of the stepping OdeWorld.
// ODE keeps these handlers per process; installing them process-wide is
// right because they hold no state: the exception goes up the stack of
// whichever thread called ODE, to its own OdeWorld. Idempotent: every
// OdeWorld calls it, and it re-installs them if something replaced them.
void InstallOdeHandlers();

class OdeSoil;  // ode_soil.h: wheels on soft soil

class OdeWorld : public PhysicsEngine {
 public:
  // model and its World must outlive this object. Throws OdeError when
  // ODE refuses a part (e.g. an inertia it finds not positive definite).
  OdeWorld(const model::FlatModel& model, const Parameters& params);
  ~OdeWorld() override;
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  const char* name() const override { return "ode"; }
  // Collide, step (dWorldStep or dWorldQuickStep), empty the contact group.
  // Throws OdeError when ODE fails; the world is dead from then on.
  void Step() override;
  bool dead() const override { return dead_; }
  // Messages ODE printed (e.g. "LCP internal error") during the last Step
  // (the first Step's include those of the construction).
  const std::vector<std::string>& last_messages() const override { return messages_; }
  int last_contact_count() const override { return contact_count_; }

  BodyReadout ReadBody(int body) const override;
  JointReadout ReadJoint(int joint) const override;
  double JointPosition(int joint, int axis) const override;
  double JointRate(int joint, int axis) const override;
  std::vector<WheelSoilReadout> ReadWheelSoil() const override;

  // Adds a force [N] at the centre of mass for the coming step (ODE clears
  // accumulated forces after each step).
  void ZeroVelocities() override;
  void AddForce(int body, const Eigen::Vector3d& force) override;

  // Velocity motor of one joint axis (ODE's built-in joint motor).
  void SetMotor(int joint, int axis, double velocity, double max_force) override;
  void SetStops(int joint, int axis, double lo, double hi) override;

  std::vector<ContactReadout> ReadContacts() const override;

  // Distance along the ray to the first geom hit (range when nothing is
  // hit); geoms of exclude_body are ignored (the scanner's own housing).
  double CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double range,
                 int exclude_body) override;

  // ODE's collide (plain contacts of the world's contactMu), step, empty
  // the group: the bare column of bench/sim_bench.
  void BareStep() override;

 private:
  struct Body {
    dBodyID body = nullptr;          // null for static objects
    dGeomID geom = nullptr;          // null for point masses
    Eigen::Vector3d com = Eigen::Vector3d::Zero();  // body frame
  };
  struct Joint {
    dJointID joint = nullptr;
    dJointFeedback feedback{};
    model::JointKind kind = model::JointKind::kFixed;
    // ODE's angle at the last step and the continuous angle made of the
    // changes added up since construction, per axis.
    double wrapped[3] = {0, 0, 0};
    double continuous[3] = {0, 0, 0};
  };
  struct ContactRecord {
    int body1, body2;                // flat body indices, -1 = world
    dJointFeedback* feedback;
    dGeomID geom1, geom2;            // geom1 has a body; normal points into it
    Eigen::Vector3d position, normal;
    Eigen::Vector3d rolling = Eigen::Vector3d::Zero();  // contact_rules.h; zero: none
  };
  // One contact point as it ended the last step: what an isotropic
  // contact at about the same place needs to approximate Coulomb's cone
  // this step (Collide).
  struct LastContact {
    dGeomID geom1, geom2;
    Eigen::Vector3d position;
    double load;                     // [N] along the normal
    Eigen::Vector3d friction;        // [N] on geom1's body, in the contact plane
  };
  void Build();
  // Adds each rotational axis's change since the last call to its
  // continuous angle. Called after every step, so a wheel may turn up to
  // half a turn per step before a change is mistaken for its opposite.
  void TrackContinuousAngles(bool first);
  // Marks the world dead and returns the error to throw, naming the bodies
  // whose state is out of range.
  OdeError Fail(const OdeError& raised, const std::string& during);
  std::vector<std::string> SuspectBodies() const;

  double CastRayUnguarded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                          double range, int exclude_body);
  static void NearCallback(void* data, dGeomID o1, dGeomID o2);
  static void BareNearCallback(void* data, dGeomID o1, dGeomID o2);
  void Collide(dGeomID o1, dGeomID o2);
  model::SurfaceProperties Surface(const std::string& material) const;
  dJointFeedback* NextFeedback();
  void SetJointParam(int joint, int parameter, double value);

  const model::FlatModel& model_;
  const Parameters& params_;
  // Each world steps with its own (self-threaded) job list: ODE's default
  // one is shared by the process, and an error thrown out of a step leaves
  // jobs in it that would break every later world (and abort in
  // dCloseODE). A dead world's list is abandoned with it.
  dThreadingImplementationID threading_ = nullptr;
  bool dead_ = false;
  bool first_step_ = true;
  int building_body_ = -1;           // during construction, for messages
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  dHeightfieldDataID heightfield_data_ = nullptr;
  std::vector<Body> bodies_;
  std::vector<std::unique_ptr<Joint>> joints_;   // stable feedback addresses
  struct GeomInfo {
    int body;                        // flat body index, -1 = plane/heightfield/static
    int owner_body;                  // flat body index even for static objects
    model::SurfaceProperties surface;
    // Unit axis in the geom frame the body spins about (model::SpinAxis:
    // its one hinge, or a cylinder's axis) when it has one; a "rolling"
    // pair takes its rolling direction from the geom of the two that has.
    Eigen::Vector3d spin_axis = Eigen::Vector3d::Zero();
    bool has_spin_axis = false;
  };
  // The geom's spin axis in the world frame, none when it has none.
  std::optional<Eigen::Vector3d> WorldSpinAxis(const GeomInfo& info, dGeomID geom) const;
  // The sliding velocity of o1 against o2 at the contact, in its plane.
  Eigen::Vector3d SlipVelocity(dGeomID o1, dGeomID o2, const dContactGeom& contact) const;
  std::vector<GeomInfo> geom_info_;  // dGeomGetData = index + 1
  std::vector<dContact> contact_buffer_;
  // Contact feedback storage in fixed chunks so addresses stay valid while
  // ODE writes into them during the step.
  std::vector<std::unique_ptr<dJointFeedback[]>> feedback_chunks_;
  size_t feedback_used_ = 0;
  std::vector<ContactRecord> contact_records_;
  // Wheels on soil (null: no ground of soil). Their contact joints are
  // in contact_records_; what the soil adds as plain forces, per body:
  std::unique_ptr<OdeSoil> soil_;
  // The heightfield's geom (null: none) and its pose, for rays
  // (ray_heightfield.h).
  dGeomID heightfield_geom_ = nullptr;
  Eigen::Isometry3d heightfield_pose_ = Eigen::Isometry3d::Identity();
  struct SoilPush {
    int body;
    Eigen::Vector3d force, torque;  // torque about the centre of mass
    SoilContactRows rows;           // and the contact joint's rows
    dJointFeedback* feedback;       // what they carried
  };
  std::vector<SoilPush> soil_pushes_;
  // The soil's contact of wheel o1 (body b1) with ground o2; false when o1
  // is no wheel (collided as rigid ground, said once per body).
  bool CollideWithSoil(dGeomID o1, dBodyID b1, dGeomID o2);
  std::vector<LastContact> last_contacts_;  // sorted by (geom1, geom2)
  void RecordLastContacts();
  // The last step's contact points of the pair, [first, second).
  std::pair<const LastContact*, const LastContact*> LastContactsOf(dGeomID geom1,
                                                                   dGeomID geom2) const;
  // The pair's load at the last step over the mass of its bodies (each
  // inverse mass added): the acceleration their friction gives per unit
  // mu, so mu h LoadPerMass is the slip one step of friction can stop.
  // g on a pair that did not touch (its own weight is all that is known).
  // The bodies' own masses, not what the joints add to them: a wheel of a
  // robot stops faster by this than it does, which errs to the implicit
  // branch of the cone (Collide), stable for any slip.
  double LoadPerMass(dGeomID geom1, dBodyID b1, dGeomID geom2, dBodyID b2) const;
  // The last step's contact point of the pair nearest to position, or
  // nullptr when the pair did not touch.
  const LastContact* NearestLastContact(dGeomID geom1, dGeomID geom2,
                                        const Eigen::Vector3d& position) const;
  std::vector<Eigen::Vector3d> contact_force_, contact_torque_;
  std::vector<std::string> messages_;
  int contact_count_ = 0;
  double gravity_ = 0.0;  // [m/s^2] |g|: a new contact's load per mass (LoadPerMass)
  // Ray casting state (the ray geom lives outside the space).
  dGeomID ray_ = nullptr;
  int ray_exclude_body_ = -1;
  double ray_hit_ = 0.0;
};

}  // namespace simpartner::sim
