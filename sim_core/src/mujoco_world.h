// The MuJoCo engine (Debian's libmujoco 2.2): the flat model built as an
// MJCF in memory (a virtual file, nothing on disk) in our own frame, y up,
// and stepped so that it behaves as ODE's contacts and motors do where
// MuJoCo can, and says where it cannot. docs/engines.md derives each
// mapping; in short:
//   - contacts: ODE's per-step law (a penetration r corrected by ERP r / h
//     within the step, the constraint giving way by CFM) as MuJoCo's
//     reference acceleration and regularizer, per contact point, with our
//     own rule for combining two materials; friction on Coulomb's elliptic
//     cone, its first direction set as ODE's sim sets it (a wheel's
//     rolling direction) for anisotropic materials; bounce through the
//     reference velocity of the normal row;
//   - motors: ODE's velocity motor (reach the velocity within a step, up
//     to a force limit) as a stiff velocity servo integrated implicitly,
//     or the limit force itself when the servo would pass it;
//   - stops: MuJoCo joint limits with the same per-step law as contacts.
// The contact rules are ODE's and ours, in contact_rules.h, applied as
// they are on ODE. Internal to sim_core: MuJoCo's headers stay in
// sim_core/src/mujoco_*.cpp (the world, its contacts, its MJCF).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/model/body_tree.h"
#include "simpartner/model/surface.h"
#include "simpartner/sim/engine.h"
#include "soil_contact.h"

struct mjModel_;
struct mjData_;
struct mjContact_;

namespace simpartner::sim {

class MujocoWorld : public PhysicsEngine {
 public:
  // model and its World must outlive this object. Throws EngineError when
  // the model has what MuJoCo cannot represent (MujocoLimits) or MuJoCo
  // refuses it.
  MujocoWorld(const model::FlatModel& model, const Parameters& params);
  ~MujocoWorld() override;
  MujocoWorld(const MujocoWorld&) = delete;
  MujocoWorld& operator=(const MujocoWorld&) = delete;

  const char* name() const override { return "mujoco"; }
  void Step() override;
  bool dead() const override { return dead_; }
  const std::vector<std::string>& last_messages() const override { return messages_; }
  int last_contact_count() const override { return contact_count_; }

  BodyReadout ReadBody(int body) const override;
  JointReadout ReadJoint(int joint) const override;
  double JointPosition(int joint, int axis) const override;
  double JointRate(int joint, int axis) const override;
  std::vector<ContactReadout> ReadContacts() const override;
  std::vector<WheelSoilReadout> ReadWheelSoil() const override;
  void ZeroVelocities() override;
  void AddForce(int body, const Eigen::Vector3d& force) override;
  void SetMotor(int joint, int axis, double velocity, double max_force) override;
  void SetStops(int joint, int axis, double lo, double hi) override;
  double CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double range,
                 int exclude_body) override;

  // MuJoCo's own mj_step on this model with the motors as set, none of
  // our contact set-up: the bare column of bench/sim_bench.
  void BareStep() override;

 private:
  // One of our joints in MuJoCo: up to two MuJoCo joints (one per axis) in
  // the child body.
  struct JointMap {
    int child = -1, parent = -1;  // flat bodies; parent -1 = the world
    bool child_is_body1 = true;
    int axes = 0;
    // MuJoCo's joints, one per axis (a ball joint: one, no axis). MuJoCo's
    // axis is ours turned round when body1 is the parent, so its values
    // (the child relative to the parent) count as ours (body1 relative to
    // body2).
    int mj_joint[2] = {-1, -1};
    int qpos[2] = {-1, -1};
    int dof[2] = {-1, -1};
    int actuator[2] = {-1, -1};
  };
  struct Motor {
    double velocity = 0.0;        // ours
    double max_force = 0.0;       // 0 = no motor (ODE's default)
    double kv = 0.0;              // [N m s/rad] or [N s/m] of the servo
  };
  struct GeomInfo {
    int body = -1;                // flat body owning it; -1 = plane or heightfield
    model::SurfaceProperties surface;
    Eigen::Vector3d spin_axis = Eigen::Vector3d::Zero();  // body frame
    bool has_spin_axis = false;
  };

  void Load(const std::string& xml);
  void MapElements(const model::BodyTree& tree);
  void MapGeoms();
  void MapJoints(const model::BodyTree& tree);
  void SetInitialVelocities();
  void FillHeightfield();
  // mj_step1 with our contact set-up between collision and constraints.
  void Prepare();
  // Kinematics and velocities of the state after a step.
  void UpdateReadouts();
  void SetUpContacts();
  // A contact point's softness and coefficients from its pair's material
  // (shared among `points` points when it has a physical stiffness).
  void SetUpMaterial(const model::SurfaceProperties& combined, int points,
                     mjContact_* contact) const;
  // Its friction frame (the first tangent along rolling, when an
  // anisotropic contact has one), and whether it slides or rolls
  // (AppliedFriction).
  void SetUpFriction(int index, const model::SurfaceProperties& combined,
                     const Eigen::Vector3d* rolling);
  // Friction applied to a contact rather than solved by MuJoCo: sliding
  // (a slip one step of friction cannot stop), rolling resistance (a roll
  // it cannot stop). Per newton of load, on geom1; then as applied.
  struct AppliedFriction {
    int contact = -1;
    Eigen::Vector3d force_per_newton = Eigen::Vector3d::Zero();
    Eigen::Vector3d torque_per_newton = Eigen::Vector3d::Zero();
    double stop_torque = INFINITY;  // [N m] what stops the roll within the step
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  };
  enum class Slide { kHolds, kOneWay, kBothWays };
  // Isotropic friction (Coulomb's cone): slides, or holds.
  Slide Slides(const mjContact_& contact, const model::SurfaceProperties& surface,
               AppliedFriction* sliding) const;
  // Anisotropic friction (ODE's box, mu and mu2 apart): each direction
  // slides or holds; one way, contact's frame and coefficients are set so
  // that MuJoCo holds the other.
  Slide SlidesBox(mjContact_* contact, const model::SurfaceProperties& surface,
                  AppliedFriction* sliding) const;
  bool Rolls(const mjContact_& contact, const model::SurfaceProperties& surface, bool slides,
             AppliedFriction* applied) const;
  void ApplyFriction();
  // 3 x nv: the velocity (or with rotation, the angular velocity) of
  // contact's point on geom1's body relative to geom2's, per generalized
  // velocity. In scratch_, valid until the next call.
  using Jacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
  const Jacobian& RelativeJacobian(const mjContact_& contact, bool rotation = false) const;
  // The inverse inertia of contact's point along `direction` (J M^-1 J^T
  // of the Jacobian `jac`, a unit direction).
  double InverseInertia(const Jacobian& jac, const Eigen::Vector3d& direction) const;
  // The motor of actuator holds its velocity this step (its limit allows
  // the force that takes) rather than push with its limit.
  bool ServoHolds(int actuator) const;
  // The load [N] of the point of the last step nearest to contact, of the
  // same pair of geoms; none for a new one.
  std::optional<double> LastLoad(const mjContact_& contact) const;
  // The slip [m/s] friction of coefficient mu takes off contact's point in
  // one step, its effective inverse mass along the slip inverse_inertia.
  double Brake(const mjContact_& contact, double mu, double inverse_inertia) const;
  void SetUpNormals();
  void SetUpMotors();
  void CollectForces();
  void CollectJointForces();
  // Velocity of a point fixed to a MuJoCo body (0 = the world).
  Eigen::Vector3d PointVelocity(int mj_body, const Eigen::Vector3d& point) const;
  // The geom's spin axis in the world frame, none when it has none.
  std::optional<Eigen::Vector3d> WorldSpinAxis(int geom) const;
  void CheckWarnings();
  EngineError Fail(const std::string& message, const std::string& during);
  std::vector<std::string> SuspectBodies() const;
  // Solver reference and impedance of the per-step law for a row whose
  // approximate inverse inertia is inverse_inertia.
  void StepLaw(double erp, double cfm, double inverse_inertia, double solref[2],
               double solimp[5]) const;
  Eigen::Vector3d Up(const double* v) const;

  // Soil (mujoco_soil.cpp): a wheel (a cylinder) or a plate on a ground of
  // soil meets the rows of soil_contact.h instead of MuJoCo's contact,
  // solved with the step (backward in time, as ODE solves them) and
  // applied before MuJoCo's constraint solve.
  struct SoilBody {
    int geom = -1;   // the wheel's (or plate's) MuJoCo geom
    SoilContactRows rows;
    Eigen::Vector3d row_force = Eigen::Vector3d::Zero();  // the rows' solved force, at rows.point
    // All the soil's force on the body, and its torque about the body's
    // centre of mass: what the step applied.
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  };
  void MapSoil();
  bool IsWheel(int geom) const;
  // A box, sphere or capsule of a moving body: it meets soil as a plate.
  bool IsPlate(int geom) const;
  // After mj_collision: drops MuJoCo's contacts of wheels and plates with
  // a ground of soil (the soil answers them).
  void DropSoilContacts();
  WheelState WheelStateOf(int geom) const;
  PlateState PlateOf(int geom) const;
  // The rows of `geom` on each ground of soil it presses, into on_soil_.
  void CollectSoilContacts(int geom);
  // The soil's forces of this step onto the bodies (xfrc_applied).
  void ApplySoil();
  // The rows' forces of on_soil_ (SoilBody::row_force), from the plain
  // forces' acceleration (soil_scratch_.qacc).
  void SolveSoilRows();
  void CollectSoilForces();

  const model::FlatModel& model_;
  const Parameters& params_;
  mjModel_* m_ = nullptr;
  mjData_* d_ = nullptr;
  bool dead_ = false;
  bool first_step_ = true;
  std::vector<std::string> messages_;
  int contact_count_ = 0;
  std::vector<int> body_id_;       // flat body -> MuJoCo body (0 for static ones)
  std::vector<int> flat_body_;     // MuJoCo body -> flat body (-1: the world)
  std::vector<JointMap> joints_;   // per flat joint
  std::vector<Motor> motors_;      // per MuJoCo actuator
  std::vector<GeomInfo> geoms_;    // per MuJoCo geom
  std::vector<Eigen::Vector3d> contact_force_, contact_torque_;
  std::vector<JointReadout> joint_forces_;   // per flat joint, of the last step
  std::vector<model::SurfaceProperties> contact_surface_;  // per MuJoCo contact
  std::vector<Eigen::Vector3d> contact_rolling_;  // per MuJoCo contact; zero: none
  std::vector<AppliedFriction> applied_;                    // this step's applied friction
  struct LastLoad_ {
    int geom1, geom2;
    Eigen::Vector3d position;
    double load;
  };
  std::vector<LastLoad_> last_loads_;                       // the last step's contact points
  std::vector<int> warning_counts_;
  double gravity_ = 0.0;
  // Working space of the contact set-up, sized once (nv): a step
  // allocates nothing for its contacts.
  struct Scratch {
    Jacobian jac1, jac2, jac;
    Eigen::VectorXd row, solved;
    std::vector<int> points;  // per contact: points of its pair of geoms
  };
  mutable Scratch scratch_;
  std::unique_ptr<SoilContacts> soil_;
  std::vector<int> soil_ground_;        // per MuJoCo geom: its ground in soil_; -1: none
  std::vector<int> soil_ground_geoms_;  // the geoms that are grounds of soil
  std::vector<int> soil_pressers_;      // the wheels and plates: the geoms that meet soil
  // Per MuJoCo geom, this step: bit g set where MuJoCo's collision found
  // it against ground g of soil_ (a world has two at most: its plane and
  // its heightfield).
  std::vector<uint32_t> soil_met_;
  std::vector<SoilBody> on_soil_;      // this step's wheels on soil
  // Working space of the soil's rows, resized only when their number
  // changes: a step on soil allocates nothing.
  struct SoilScratch {
    Eigen::VectorXd qfrc, qacc;  // the plain forces, generalized, and their acceleration
    Eigen::VectorXd vel;         // the velocities the step would give without the rows
    Jacobian point_jac;
    // J, then D^-1/2 L^-T J^T (rows x nv), for M = L^T D L.
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J, X;
    Eigen::MatrixXd Q;
    Eigen::VectorXd v_free, c, d, lo, hi, q, f;
    Eigen::LDLT<Eigen::MatrixXd> ldlt;
  };
  SoilScratch soil_scratch_;
};

// What of model MuJoCo cannot represent, each naming the element with its
// file and line: joints that close a loop of bodies.
std::vector<Diagnostic> MujocoLimits(const model::FlatModel& model, const Parameters& params);

}  // namespace simpartner::sim
