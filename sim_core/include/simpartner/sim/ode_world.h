// ODE objects built from a FlatModel: bodies, geoms, joints, the collision
// space, plane and heightfield. One Step() is collide, step, empty the
// contact group (ODE's demo_buggy loop), with contact forces summed per body
// from joint feedback. Everything given to ODE was validated by the loader.
#pragma once

#include <ode/ode.h>

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/parameters.h"
#include "simpartner/sim/flat_model.h"

namespace simpartner::sim {

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
  double rate[3] = {0, 0, 0};
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  Eigen::Vector3d force1 = Eigen::Vector3d::Zero(), torque1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d force2 = Eigen::Vector3d::Zero(), torque2 = Eigen::Vector3d::Zero();
};

// Contact properties of one geom, resolved from its material name.
struct SurfaceProperties {
  double mu = 1.0, bounce = 0.0, bounce_velocity = 0.1;
  double soft_erp = 0.2, soft_cfm = 1e-5, rolling_friction = 0.0;
};

// A material's contact properties; a geom without one (nullptr) takes the
// contact defaults of the parameters.
SurfaceProperties ResolveSurface(const model::Material* material, const Parameters& params);
// The contact between two surfaces, as the sim makes it: friction and
// rolling resistance the smaller, bounce the larger, softness the softer
// (smaller ERP, larger CFM) of the two.
SurfaceProperties CombineSurfaces(const SurfaceProperties& a, const SurfaceProperties& b);

class OdeWorld {
 public:
  // model and its World must outlive this object.
  OdeWorld(const FlatModel& model, const Parameters& params);
  ~OdeWorld();
  OdeWorld(const OdeWorld&) = delete;
  OdeWorld& operator=(const OdeWorld&) = delete;

  // Collide, step (dWorldStep or dWorldQuickStep), empty the contact group.
  void Step();
  // Messages ODE printed (e.g. "LCP internal error") during the last Step.
  const std::vector<std::string>& last_messages() const { return messages_; }
  int last_contact_count() const { return contact_count_; }

  BodyReadout ReadBody(int body) const;
  JointReadout ReadJoint(int joint) const;
  double JointPosition(int joint, int axis) const;
  double JointRate(int joint, int axis) const;

  // Adds a force [N] at the centre of mass for the coming step (ODE clears
  // accumulated forces after each step).
  void AddForce(int body, const Eigen::Vector3d& force);

  // Velocity motor of one joint axis (ODE's built-in joint motor).
  void SetMotor(int joint, int axis, double velocity, double max_force);
  void SetStops(int joint, int axis, double lo, double hi);

  // Distance along the ray to the first geom hit (range when nothing is
  // hit); geoms of exclude_body are ignored (the scanner's own housing).
  double CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double range,
                 int exclude_body);

  // Raw handles for the benchmark's bare-ODE comparison.
  dWorldID world() const { return world_; }
  dSpaceID space() const { return space_; }

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
  };
  struct ContactRecord {
    int body1, body2;                // flat body indices, -1 = world
    dJointFeedback* feedback;
  };

  static void NearCallback(void* data, dGeomID o1, dGeomID o2);
  void Collide(dGeomID o1, dGeomID o2);
  SurfaceProperties Surface(const std::string& material) const;
  dJointFeedback* NextFeedback();
  void SetJointParam(int joint, int parameter, double value);
  double GetJointParam(int joint, int parameter) const;

  const FlatModel& model_;
  const Parameters& params_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  dHeightfieldDataID heightfield_data_ = nullptr;
  std::vector<Body> bodies_;
  std::vector<std::unique_ptr<Joint>> joints_;   // stable feedback addresses
  struct GeomInfo {
    int body;                        // flat body index, -1 = plane/heightfield/static
    int owner_body;                  // flat body index even for static objects
    SurfaceProperties surface;
  };
  std::vector<GeomInfo> geom_info_;  // dGeomGetData = index + 1
  std::vector<dContact> contact_buffer_;
  // Contact feedback storage in fixed chunks so addresses stay valid while
  // ODE writes into them during the step.
  std::vector<std::unique_ptr<dJointFeedback[]>> feedback_chunks_;
  size_t feedback_used_ = 0;
  std::vector<ContactRecord> contact_records_;
  std::vector<Eigen::Vector3d> contact_force_, contact_torque_;
  std::vector<std::string> messages_;
  int contact_count_ = 0;
  // Ray casting state (the ray geom lives outside the space).
  dGeomID ray_ = nullptr;
  int ray_exclude_body_ = -1;
  double ray_hit_ = 0.0;
};

}  // namespace simpartner::sim
