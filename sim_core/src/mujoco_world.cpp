#include "mujoco_world.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "contact_rules.h"
#include "mujoco_mjcf.h"
#include "simpartner/model/flat_model.h"

namespace simpartner::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The motor servo's gain, in units of the axis's own inertia per step: an
// implicit step closes kServoGain / (1 + kServoGain) of the gap to the
// target velocity (99 %), and a load torque tau leaves a velocity error of
// tau h / (kServoGain M).
constexpr double kServoGain = 100.0;

// MuJoCo's fatal errors (mju_error) would exit the process; they become an
// exception of the thread that called MuJoCo, as ODE's do. Its warnings
// would go to stdout and a MUJOCO_LOG.TXT in the working directory; the
// engine reads the warning counters of its mjData instead.
void MujocoFatal(const char* message) {
  throw EngineError("MuJoCo", message, "", {});
}
void MujocoWarning(const char*) {}

void InstallMujocoHandlers() {
  if (mju_user_error != &MujocoFatal) mju_user_error = &MujocoFatal;
  if (mju_user_warning != &MujocoWarning) mju_user_warning = &MujocoWarning;
}

Eigen::Vector3d V(const mjtNum* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

// Into [-pi, pi], as std::remainder puts it; an angle already there (the
// usual case) skips the library call, with the same result.
double Wrap(double angle) {
  return std::abs(angle) <= kPi ? angle : std::remainder(angle, 2 * kPi);
}

}  // namespace

namespace {

// The joints of model that close a loop in tree, at their file and line.
std::vector<Diagnostic> LoopsOf(const model::FlatModel& model, const model::BodyTree& tree) {
  std::vector<Diagnostic> out;
  for (int j : tree.loop_joints) {
    const model::FlatJoint& joint = model.joints[static_cast<size_t>(j)];
    out.push_back(Diagnostic{joint.source->where.file, joint.source->where.line, "joint",
                             "joint '" + joint.name +
                                 "' closes a loop of bodies: the MuJoCo engine hangs bodies in "
                                 "a tree and has no place for it (--engine=ode runs it)"});
  }
  return out;
}

}  // namespace

std::vector<Diagnostic> MujocoLimits(const model::FlatModel& model, const Parameters&) {
  return LoopsOf(model, model::BuildBodyTree(model));
}

MujocoWorld::MujocoWorld(const model::FlatModel& model, const Parameters& params)
    : model_(model), params_(params) {
  InstallMujocoHandlers();
  const model::BodyTree tree = model::BuildBodyTree(model);
  const std::vector<Diagnostic> limits = LoopsOf(model, tree);
  if (!limits.empty()) throw EngineError("MuJoCo", limits.front().Format(), "building", {});
  Load(EngineMjcf(model, tree, params));
  MapElements(tree);
  MapSoil();
  gravity_ = model.world->gravity.norm();
  SetStopsOfTheFiles(model, this);
  SetInitialVelocities();
  UpdateReadouts();
}

MujocoWorld::~MujocoWorld() {
  if (d_ != nullptr) mj_deleteData(d_);
  if (m_ != nullptr) mj_deleteModel(m_);
}

void MujocoWorld::Load(const std::string& xml) {
  // mjVFS holds 2,000 file names of 1,000 bytes: on the heap.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "simpartner.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0)
    throw EngineError("MuJoCo", "cannot make its in-memory model file", "building", {});
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], xml.data(), xml.size());
  char error[1000] = "";
  m_ = mj_loadXML(name, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (m_ == nullptr) throw EngineError("MuJoCo", error, "building the model", {});
  d_ = mj_makeData(m_);
  FillHeightfield();
}

void MujocoWorld::FillHeightfield() {
  const model::World& world = *model_.world;
  if (!world.heightfield) return;
  const model::Heightfield& h = *world.heightfield;
  double low = INFINITY, high = -INFINITY;
  for (double s : h.samples) {
    low = std::min(low, h.scale * s + h.offset);
    high = std::max(high, h.scale * s + h.offset);
  }
  // MuJoCo's elevations are 0..1 times size[2] above the geom: the geom
  // goes to the lowest height and size[2] spans the rest.
  const double span = std::max(high - low, 1e-9);
  m_->hfield_size[2] = span;
  const int field = mj_name2id(m_, mjOBJ_GEOM, kMjcfField);
  const Eigen::Vector3d up = world.Up();
  for (int k = 0; k < 3; ++k) m_->geom_pos[3 * field + k] += low * up[k];
  // MuJoCo's row r is our row rows-1-r (its y is our -z).
  float* data = m_->hfield_data + m_->hfield_adr[0];
  for (int r = 0; r < h.rows; ++r)
    for (int c = 0; c < h.columns; ++c)
      data[r * h.columns + c] = static_cast<float>(
          (h.scale * h.samples[static_cast<size_t>((h.rows - 1 - r) * h.columns + c)] + h.offset -
           low) /
          span);
}

void MujocoWorld::MapElements(const model::BodyTree& tree) {
  body_id_.assign(model_.bodies.size(), 0);
  flat_body_.assign(static_cast<size_t>(m_->nbody), -1);
  for (size_t b = 0; b < model_.bodies.size(); ++b) {
    if (model_.bodies[b].source->is_static) continue;
    body_id_[b] = mj_name2id(m_, mjOBJ_BODY, MjcfBodyName(static_cast<int>(b)).c_str());
    flat_body_[static_cast<size_t>(body_id_[b])] = static_cast<int>(b);
  }
  MapGeoms();
  MapJoints(tree);
  contact_force_.assign(model_.bodies.size(), Eigen::Vector3d::Zero());
  contact_torque_.assign(model_.bodies.size(), Eigen::Vector3d::Zero());
  joint_forces_.assign(model_.joints.size(), JointReadout{});
  warning_counts_.assign(mjNWARNING, 0);
}

void MujocoWorld::MapGeoms() {
  const model::World& world = *model_.world;
  // A material by name as the ODE side finds it (the loader checked it).
  auto surface_of = [&](const std::string& material) {
    return model::ResolveSurface(material.empty() ? nullptr : world.FindMaterial(material),
                                 params_);
  };
  geoms_.assign(static_cast<size_t>(m_->ngeom), GeomInfo{});
  for (int g = 0; g < m_->ngeom; ++g) {
    const char* name = mj_id2name(m_, mjOBJ_GEOM, g);
    GeomInfo& info = geoms_[static_cast<size_t>(g)];
    if (std::strcmp(name, kMjcfPlane) == 0) {
      info.surface = surface_of(world.plane_material);
    } else if (std::strcmp(name, kMjcfField) == 0) {
      info.surface = surface_of(world.heightfield->material);
    } else {
      info.body = std::atoi(name + 1);
      const model::FlatBody& flat = model_.bodies[static_cast<size_t>(info.body)];
      info.surface = surface_of(flat.source->material);
      const std::vector<model::Joint>& joints =
          flat.robot < 0 ? world.joints : world.robots[static_cast<size_t>(flat.robot)].robot.joints;
      if (const auto axis = model::SpinAxis(*flat.source, joints)) {
        info.spin_axis = *axis;
        info.has_spin_axis = true;
      }
    }
  }
}

void MujocoWorld::MapJoints(const model::BodyTree& tree) {
  joints_.assign(model_.joints.size(), JointMap{});
  motors_.assign(static_cast<size_t>(m_->nu), Motor{});
  for (size_t b = 0; b < tree.nodes.size(); ++b) {
    const model::TreeNode& node = tree.nodes[b];
    if (node.joint < 0) continue;
    JointMap& map = joints_[static_cast<size_t>(node.joint)];
    map.child = static_cast<int>(b);
    map.parent = node.parent;
    map.child_is_body1 = !node.joint_reversed;
    map.axes = model_.joints[static_cast<size_t>(node.joint)].num_axes;
    // A ball joint has no axis but a MuJoCo joint, which holds its anchor.
    map.mj_joint[0] = mj_name2id(m_, mjOBJ_JOINT, MjcfJointName(node.joint, 0).c_str());
    for (int a = 0; a < map.axes; ++a) {
      const int id = mj_name2id(m_, mjOBJ_JOINT, MjcfJointName(node.joint, a).c_str());
      map.mj_joint[a] = id;
      map.qpos[a] = m_->jnt_qposadr[id];
      map.dof[a] = m_->jnt_dofadr[id];
      const int actuator = mj_name2id(m_, mjOBJ_ACTUATOR, MjcfActuatorName(node.joint, a).c_str());
      map.actuator[a] = actuator;
      motors_[static_cast<size_t>(actuator)].kv =
          kServoGain * m_->dof_M0[map.dof[a]] / params_.stepsize;
    }
  }
}

void MujocoWorld::SetInitialVelocities() {
  // A floating root moves as the file says (MuJoCo's free joint: the
  // velocity of the body origin in the world, the angular one in the body
  // frame); a joint moves at the relative velocity along its axis.
  for (size_t b = 0; b < model_.bodies.size(); ++b) {
    const model::FlatBody& flat = model_.bodies[b];
    if (flat.source->is_static) continue;
    const int id = body_id_[b];
    const int joint = m_->body_jntadr[id];
    if (joint < 0 || m_->jnt_type[joint] != mjJNT_FREE) continue;
    const int dof = m_->jnt_dofadr[joint];
    const Eigen::Vector3d w = flat.pose.linear().transpose() * flat.angular_velocity;
    for (int k = 0; k < 3; ++k) {
      d_->qvel[dof + k] = flat.linear_velocity[k];
      d_->qvel[dof + 3 + k] = w[k];
    }
  }
  for (size_t j = 0; j < joints_.size(); ++j) {
    const JointMap& map = joints_[j];
    if (map.axes == 0) continue;
    const model::FlatJoint& joint = model_.joints[j];
    const model::FlatBody& child = model_.bodies[static_cast<size_t>(map.child)];
    Eigen::Vector3d w = child.angular_velocity, v = child.linear_velocity;
    if (map.parent >= 0) {
      const model::FlatBody& parent = model_.bodies[static_cast<size_t>(map.parent)];
      w -= parent.angular_velocity;
      v -= parent.linear_velocity + parent.angular_velocity.cross(child.pose.translation() -
                                                                   parent.pose.translation());
    }
    const bool hinge = joint.source->kind != model::JointKind::kSlider;
    for (int a = 0; a < map.axes; ++a)
      d_->qvel[map.dof[a]] = (map.child_is_body1 ? 1.0 : -1.0) * joint.axis[a].dot(hinge ? w : v);
  }
}

void MujocoWorld::Prepare() {
  // mj_step1 without sensors and energy, in an order that knows the smooth
  // forces' acceleration (qacc_smooth) before the contacts are set up:
  // whether a contact will slide depends on what the motors ask of it.
  // Kinematics, centres of mass and body velocities of this state are
  // UpdateReadouts' of the last step (or of the construction).
  mj_checkPos(m_, d_);
  mj_checkVel(m_, d_);
  mj_camlight(m_, d_);
  mj_tendon(m_, d_);
  mj_crb(m_, d_);
  mj_factorM(m_, d_);
  mj_transmission(m_, d_);
  // mj_fwdVelocity less the constraints' reference (they are not made yet).
  mju_mulMatVec(d_->actuator_velocity, d_->actuator_moment, d_->qvel, m_->nu, m_->nv);
  mj_passive(m_, d_);
  mj_rne(m_, d_, 0, d_->qfrc_bias);
  mj_fwdActuation(m_, d_);
  mj_fwdAcceleration(m_, d_);
  mj_collision(m_, d_);
  DropSoilContacts();
  SetUpContacts();
  mj_makeConstraint(m_, d_);
  mj_projectConstraint(m_, d_);
  mj_referenceConstraint(m_, d_);
  SetUpNormals();
}

bool MujocoWorld::ServoHolds(int actuator) const {
  // ODE's motor reaches its velocity within the step when the force that
  // takes is within its limit: about the axis's inertia times the velocity
  // gap over the step.
  const Motor& motor = motors_[static_cast<size_t>(actuator)];
  const int dof = m_->jnt_dofadr[m_->actuator_trnid[2 * actuator]];
  const double needed = m_->dof_M0[dof] * (motor.velocity - d_->qvel[dof]) / params_.stepsize;
  return motor.max_force > 0.0 && std::abs(needed) <= motor.max_force;
}

void MujocoWorld::SetUpMotors() {
  // Below its limit, a stiff servo, force kv (v - qvel), integrated
  // backward (implicitly): (M + h kv) dv = h kv (v - qvel) + h f, which is
  // MuJoCo's semi-implicit step with h kv of armature on the axis. Unlike
  // MuJoCo 2.2's implicit integrator, the constraint solve sees it too, so
  // friction holds a driven wheel against its servo's real torque.
  // Above its limit, the limit force itself.
  const double h = params_.stepsize;
  for (int u = 0; u < m_->nu; ++u) {
    const Motor& motor = motors_[static_cast<size_t>(u)];
    const int dof = m_->jnt_dofadr[m_->actuator_trnid[2 * u]];
    mjtNum* gain = m_->actuator_gainprm + mjNGAIN * u;
    mjtNum* bias = m_->actuator_biasprm + mjNBIAS * u;
    const bool holds = ServoHolds(u);
    m_->dof_armature[dof] = holds ? h * motor.kv : 0.0;
    if (motor.max_force <= 0.0) {
      gain[0] = bias[2] = d_->ctrl[u] = 0.0;
    } else if (holds) {
      gain[0] = motor.kv;
      bias[2] = -motor.kv;
      d_->ctrl[u] = motor.velocity;
    } else {
      gain[0] = 1.0;
      bias[2] = 0.0;
      d_->ctrl[u] = std::copysign(motor.max_force, motor.velocity - d_->qvel[dof]);
    }
    // The servo's explicit force may pass the limit; the step does not
    // take more than the limit allowed for, so it is not clipped.
    const double range = holds ? 1e30 : motor.max_force;
    m_->actuator_forcerange[2 * u] = -range;
    m_->actuator_forcerange[2 * u + 1] = range;
  }
}

void MujocoWorld::CollectForces() {
  contact_count_ = d_->ncon;
  for (size_t b = 0; b < contact_force_.size(); ++b) {
    contact_force_[b].setZero();
    contact_torque_[b].setZero();
  }
  last_loads_.clear();
  for (int i = 0; i < d_->ncon; ++i) {
    const mjContact& contact = d_->contact[i];
    if (contact.efc_address < 0) continue;
    mjtNum local[6];
    mj_contactForce(m_, d_, i, local);
    last_loads_.push_back(LastLoad_{contact.geom1, contact.geom2, V(contact.pos), std::max(local[0], 0.0)});
    // The frame's rows are the normal (from geom1 to geom2) and the two
    // tangents; the force is the one geom1 exerts on geom2.
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    for (int r = 0; r < 3; ++r) {
      force += local[r] * V(contact.frame + 3 * r);
      torque += local[3 + r] * V(contact.frame + 3 * r);
    }
    const Eigen::Vector3d at = V(contact.pos);
    for (const AppliedFriction& a : applied_) {
      if (a.contact != i) continue;
      force -= a.force;  // what was applied on geom1, on geom2
      torque -= a.torque;
    }
    const int sides[2] = {contact.geom2, contact.geom1};
    for (int side = 0; side < 2; ++side) {
      const int mj_body = m_->geom_bodyid[sides[side]];
      const int b = flat_body_[static_cast<size_t>(mj_body)];
      if (b < 0) continue;
      const double s = side == 0 ? 1.0 : -1.0;
      contact_force_[static_cast<size_t>(b)] += s * force;
      contact_torque_[static_cast<size_t>(b)] +=
          s * ((at - V(d_->xipos + 3 * mj_body)).cross(force) + torque);
    }
  }
  if (!joints_.empty()) CollectJointForces();
}

void MujocoWorld::CollectJointForces() {
  mj_rnePostConstraint(m_, d_);
  for (size_t j = 0; j < joints_.size(); ++j) {
    const JointMap& map = joints_[j];
    JointReadout& out = joint_forces_[j];
    out = JointReadout{};
    if (map.child < 0) continue;
    // cfrc_int: what the parent exerts on the child, [torque, force] about
    // the subtree centre of mass of the child's root.
    const int child = body_id_[static_cast<size_t>(map.child)];
    const mjtNum* wrench = d_->cfrc_int + 6 * child;
    const Eigen::Vector3d force = V(wrench + 3);
    const Eigen::Vector3d at = V(d_->subtree_com + 3 * m_->body_rootid[child]);
    const Eigen::Vector3d torque = V(wrench);
    auto about = [&](int mj_body) {
      return Eigen::Vector3d(torque + (at - V(d_->xipos + 3 * mj_body)).cross(force));
    };
    Eigen::Vector3d& child_force = map.child_is_body1 ? out.force1 : out.force2;
    Eigen::Vector3d& child_torque = map.child_is_body1 ? out.torque1 : out.torque2;
    child_force = force;
    child_torque = about(child);
    if (map.parent < 0) continue;
    const int parent = body_id_[static_cast<size_t>(map.parent)];
    (map.child_is_body1 ? out.force2 : out.force1) = -force;
    (map.child_is_body1 ? out.torque2 : out.torque1) = -about(parent);
  }
}

void MujocoWorld::CheckWarnings() {
  for (int i = 0; i < mjNWARNING; ++i) {
    const int now = d_->warning[i].number;
    if (now == warning_counts_[static_cast<size_t>(i)]) continue;
    warning_counts_[static_cast<size_t>(i)] = now;
    switch (i) {
      case mjWARN_BADQPOS:
      case mjWARN_BADQVEL:
      case mjWARN_BADQACC:
        // MuJoCo has put the model back to its initial state: the run
        // cannot go on as if nothing happened.
        throw EngineError("MuJoCo",
                          std::string("a non-finite or huge ") +
                              (i == mjWARN_BADQPOS ? "position"
                               : i == mjWARN_BADQVEL ? "velocity"
                                                     : "acceleration") +
                              " in degree of freedom " + std::to_string(d_->warning[i].lastinfo),
                          "", {});
      case mjWARN_CONTACTFULL:
        messages_.push_back("MuJoCo: more contacts than its " + std::to_string(m_->nconmax) +
                            " places; the rest were dropped");
        break;
      case mjWARN_CNSTRFULL:
        messages_.push_back("MuJoCo: more constraint rows than its " +
                            std::to_string(m_->njmax) + " places; some were dropped");
        break;
      default:
        messages_.push_back("MuJoCo warning " + std::to_string(i) + " (info " +
                            std::to_string(d_->warning[i].lastinfo) + ")");
    }
  }
}

std::vector<std::string> MujocoWorld::SuspectBodies() const {
  std::vector<BodyState> moving;
  for (size_t b = 0; b < body_id_.size(); ++b) {
    if (body_id_[b] <= 0) continue;
    const BodyReadout readout = ReadBody(static_cast<int>(b));
    BodyState state;
    state.body = static_cast<int>(b);
    state.position = readout.position;
    const Eigen::Quaterniond& q = readout.orientation;
    state.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    state.linear_velocity = readout.linear_velocity;
    state.angular_velocity = readout.angular_velocity;
    moving.push_back(state);
  }
  return sim::SuspectBodies(model_, moving);
}

std::vector<ContactReadout> MujocoWorld::ReadContacts() const {
  std::vector<ContactReadout> out;
  for (int i = 0; i < d_->ncon && static_cast<size_t>(i) < contact_rolling_.size(); ++i) {
    const mjContact& contact = d_->contact[i];
    ContactReadout readout;
    readout.body1 = flat_body_[static_cast<size_t>(m_->geom_bodyid[contact.geom1])];
    readout.body2 = flat_body_[static_cast<size_t>(m_->geom_bodyid[contact.geom2])];
    readout.position = V(contact.pos);
    readout.normal = V(contact.frame);
    readout.rolling_direction = contact_rolling_[static_cast<size_t>(i)];
    out.push_back(readout);
  }
  return out;
}

EngineError MujocoWorld::Fail(const std::string& message, const std::string& during) {
  dead_ = true;
  // The bodies' positions and velocities of the state MuJoCo was left
  // with: a step that failed may have stopped before its kinematics, or
  // after MuJoCo reset the model (a huge or non-finite number), which
  // zeroes them until they are computed again.
  try {
    UpdateReadouts();
  } catch (const EngineError&) {
    // what MuJoCo cannot compute is judged as it stands
  }
  return EngineError("MuJoCo", message, during, SuspectBodies());
}

void MujocoWorld::Step() {
  if (dead_) throw EngineError("MuJoCo", "the world failed in an earlier step and cannot go on",
                               "step", SuspectBodies());
  if (!first_step_) messages_.clear();
  first_step_ = false;
  try {
    // mj_step, with our motors set before the inertia is computed (a
    // holding servo adds to it), our contact set-up between collision and
    // constraints, and the soil's forces and the sliding contacts'
    // friction applied between the smooth forces and the constraint solve.
    SetUpMotors();
    Prepare();
    CheckWarnings();
    ApplySoil();
    ApplyFriction();
    mj_fwdConstraint(m_, d_);
    mj_checkAcc(m_, d_);
    mj_Euler(m_, d_);
    CheckWarnings();
    CollectForces();
    CollectSoilForces();
    mju_zero(d_->xfrc_applied, 6 * m_->nbody);
    mju_zero(d_->qfrc_applied, m_->nv);
    UpdateReadouts();
  } catch (const EngineError& e) {
    throw Fail(e.engine_message(), "step");
  }
}

void MujocoWorld::UpdateReadouts() {
  // Positions and velocities of the new state, for readouts and rays, and
  // for the next step's Prepare.
  mj_kinematics(m_, d_);
  mj_comPos(m_, d_);
  mj_comVel(m_, d_);
}

void MujocoWorld::BareStep() {
  SetUpMotors();
  mj_step(m_, d_);
}

BodyReadout MujocoWorld::ReadBody(int index) const {
  BodyReadout out;
  out.contact_force = contact_force_[static_cast<size_t>(index)];
  out.contact_torque = contact_torque_[static_cast<size_t>(index)];
  const int id = body_id_[static_cast<size_t>(index)];
  if (id <= 0) {
    const model::FlatBody& flat = model_.bodies[static_cast<size_t>(index)];
    out.position = flat.pose.translation();
    out.orientation = Eigen::Quaterniond(flat.pose.linear());
    return out;
  }
  out.position = V(d_->xpos + 3 * id);
  const mjtNum* q = d_->xquat + 4 * id;
  out.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  // mj_objectVelocity(mjOBJ_BODY, world frame) without its call: cvel is
  // the body's spatial velocity at its tree's centre of mass; the body's
  // own centre of mass (xipos) moves at v + omega x (xipos - that centre).
  const mjtNum* cvel = d_->cvel + 6 * id;
  out.angular_velocity = V(cvel);
  out.linear_velocity =
      V(cvel + 3) + out.angular_velocity.cross(V(d_->xipos + 3 * id) -
                                               V(d_->subtree_com + 3 * m_->body_rootid[id]));
  return out;
}

double MujocoWorld::JointPosition(int joint, int axis) const {
  const JointMap& map = joints_[static_cast<size_t>(joint)];
  if (axis >= map.axes || map.qpos[axis] < 0) return 0.0;
  const double q = d_->qpos[map.qpos[axis]];
  return m_->jnt_type[map.mj_joint[axis]] == mjJNT_HINGE ? Wrap(q) : q;
}

double MujocoWorld::JointRate(int joint, int axis) const {
  const JointMap& map = joints_[static_cast<size_t>(joint)];
  if (axis >= map.axes || map.dof[axis] < 0) return 0.0;
  return d_->qvel[map.dof[axis]];
}

JointReadout MujocoWorld::ReadJoint(int index) const {
  const JointMap& map = joints_[static_cast<size_t>(index)];
  JointReadout out = joint_forces_[static_cast<size_t>(index)];
  for (int a = 0; a < map.axes; ++a) {
    out.position[a] = JointPosition(index, a);
    out.continuous_position[a] = map.qpos[a] < 0 ? 0.0 : d_->qpos[map.qpos[a]];
    out.rate[a] = JointRate(index, a);
  }
  const model::FlatJoint& flat = model_.joints[static_cast<size_t>(index)];
  const int first = map.mj_joint[0];
  if (first >= 0 && m_->jnt_type[first] != mjJNT_SLIDE) {
    out.anchor = V(d_->xanchor + 3 * first);
  } else if (flat.body1 >= 0 && body_id_[static_cast<size_t>(flat.body1)] > 0) {
    // As ODE says for fixed and slider joints: body1's centre of mass.
    out.anchor = V(d_->xipos + 3 * body_id_[static_cast<size_t>(flat.body1)]);
  }
  return out;
}

void MujocoWorld::ZeroVelocities() {
  mju_zero(d_->qvel, m_->nv);
  UpdateReadouts();
}

void MujocoWorld::AddForce(int body, const Eigen::Vector3d& force) {
  const int id = body_id_[static_cast<size_t>(body)];
  if (id <= 0) return;
  for (int k = 0; k < 3; ++k) d_->xfrc_applied[6 * id + k] += force[k];
}

void MujocoWorld::SetMotor(int joint, int axis, double velocity, double max_force) {
  const JointMap& map = joints_[static_cast<size_t>(joint)];
  if (axis >= map.axes || map.actuator[axis] < 0) return;
  Motor& motor = motors_[static_cast<size_t>(map.actuator[axis])];
  motor.velocity = velocity;
  motor.max_force = max_force;
}

void MujocoWorld::SetStops(int joint, int axis, double lo, double hi) {
  const JointMap& map = joints_[static_cast<size_t>(joint)];
  if (axis >= map.axes || map.mj_joint[axis] < 0) return;
  const int id = map.mj_joint[axis];
  m_->jnt_limited[id] = std::isfinite(lo) || std::isfinite(hi) ? 1 : 0;
  m_->jnt_range[2 * id] = std::isfinite(lo) ? lo : -1e10;
  m_->jnt_range[2 * id + 1] = std::isfinite(hi) ? hi : 1e10;
  // ODE's stops use the world's ERP and CFM.
  StepLaw(params_.JointERP(), params_.JointCFM(), m_->dof_invweight0[map.dof[axis]],
          m_->jnt_solref + mjNREF * id, m_->jnt_solimp + mjNIMP * id);
}

double MujocoWorld::CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                            double range, int exclude_body) {
  if (dead_) return range;
  const mjtNum point[3] = {origin.x(), origin.y(), origin.z()};
  const Eigen::Vector3d unit = direction.normalized();
  const mjtNum vector[3] = {unit.x(), unit.y(), unit.z()};
  // A static scanner's housing is part of MuJoCo's world body: nothing
  // is left out for it (excluding the world would hide all the ground).
  const int exclude = exclude_body >= 0 ? body_id_[static_cast<size_t>(exclude_body)] : -1;
  int geom = -1;
  const double hit = mj_ray(m_, d_, point, vector, nullptr, 1, exclude > 0 ? exclude : -1, &geom);
  return hit < 0 || hit > range ? range : hit;
}

}  // namespace simpartner::sim
