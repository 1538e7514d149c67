#include "ode_world.h"

#include "contact_rules.h"
#include "ode_convert.h"
#include "ode_soil.h"
#include "ray_heightfield.h"

#include <algorithm>
#include <utility>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>

#include "simpartner/check.h"
#include "simpartner/model/model.h"

namespace simpartner::sim {
namespace {

constexpr size_t kFeedbackChunk = 1024;

// ODE's messages (dMessage: "LCP internal error", ODE goes on) go into the
// sink of the OdeWorld stepping on this thread (set only during Step), and
// to stderr otherwise, so nothing passes silently.
thread_local std::vector<std::string>* t_message_sink = nullptr;

// A strict order of geom pairs (by address: any fixed order will do, the
// pairs are only looked up).
bool GeomPairBefore(dGeomID a1, dGeomID a2, dGeomID b1, dGeomID b2) {
  const std::less<dGeomID> before;
  return before(a1, b1) || (a1 == b1 && before(a2, b2));
}

std::string FormatOde(int number, const char* format, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  return "ODE message " + std::to_string(number) + ": " + text;
}

void OdeMessage(int number, const char* format, va_list args) {
  std::string message = FormatOde(number, format, args);
  if (t_message_sink != nullptr) {
    t_message_sink->push_back(std::move(message));
  } else {
    std::fprintf(stderr, "%s\n", message.c_str());
  }
}

// dError and dDebug call abort() or exit() when their handler returns, so
// the handler must not return: it throws. Debian's libode8 is C++ built
// with unwind tables and with its assertions on (dIASSERT, dUASSERT and
// dIVERIFY reach dDebug), and an exception passes through its frames;
// what ODE leaves behind is abandoned with the dead world (see OdeError).
[[noreturn]] void OdeFatalHandler(int number, const char* format, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  (void)number;  // 1 = internal assertion, 2 = usage error: the text says which
  throw OdeError(text, "", {});
}

// Restores the thread's message sink on every path out of a step.
class MessageSinkScope {
 public:
  explicit MessageSinkScope(std::vector<std::string>* sink) { t_message_sink = sink; }
  ~MessageSinkScope() { t_message_sink = nullptr; }
  MessageSinkScope(const MessageSinkScope&) = delete;
  MessageSinkScope& operator=(const MessageSinkScope&) = delete;
};


}  // namespace

OdeError::OdeError(std::string ode_message, std::string during, std::vector<std::string> bodies)
    : EngineError("ODE", std::move(ode_message), std::move(during), std::move(bodies)) {}

void InstallOdeHandlers() {
  static const bool initialized = [] {
    dInitODE2(0);
    return true;
  }();
  (void)initialized;
  if (dGetErrorHandler() != &OdeFatalHandler) dSetErrorHandler(&OdeFatalHandler);
  if (dGetDebugHandler() != &OdeFatalHandler) dSetDebugHandler(&OdeFatalHandler);
  if (dGetMessageHandler() != &OdeMessage) dSetMessageHandler(&OdeMessage);
}

OdeWorld::OdeWorld(const model::FlatModel& model, const Parameters& params)
    : model_(model), params_(params) {
  InstallOdeHandlers();
  try {
    // ODE's messages while building (e.g. why dMassCheck failed) become
    // warnings of the first step instead of going to stderr.
    const MessageSinkScope sink(&messages_);
    Build();
    TrackContinuousAngles(true);
  } catch (const OdeError& e) {
    // No destructor runs for a constructor that throws: the ODE objects
    // made so far are abandoned, as for a world that dies stepping.
    const std::string body =
        building_body_ >= 0 ? model::QualifiedBodyName(model_, building_body_) : "";
    const std::string during =
        body.empty() ? std::string("building the world") : "building body '" + body + "'";
    // ODE says why in a message just before the assertion (dMassCheck:
    // "inertia must be positive definite"); keep the last one.
    const std::string why = messages_.empty() ? "" : " after \"" + messages_.back() + "\"";
    throw OdeError(e.ode_message() + why, during,
                   body.empty() ? std::vector<std::string>{} : std::vector<std::string>{body});
  }
}

void OdeWorld::Build() {
  const Parameters& params = params_;
  const model::FlatModel& model = model_;
  // dWorldQuickStep may reorder constraints with ODE's random generator:
  // seeding it makes every run of the same inputs identical.
  dRandSetSeed(0);
  const model::World& world = *model.world;
  world_ = dWorldCreate();
  threading_ = dThreadingAllocateSelfThreadedImplementation();
  dWorldSetStepThreadingImplementation(world_, dThreadingImplementationGetFunctions(threading_),
                                       threading_);
  dWorldSetGravity(world_, world.gravity.x(), world.gravity.y(), world.gravity.z());
  gravity_ = world.gravity.norm();
  dWorldSetERP(world_, params.JointERP());
  dWorldSetCFM(world_, params.JointCFM());
  dWorldSetContactMaxCorrectingVel(world_, params.contactMaxCorrectingVel);
  dWorldSetContactSurfaceLayer(world_, params.contactSurfaceLayer);
  dWorldSetAutoDisableFlag(world_, params.autoDisableFlag ? 1 : 0);
  dWorldSetQuickStepNumIterations(world_, params.quickStepIterations);
  dWorldSetQuickStepW(world_, params.quickStepW);

  switch (world.collision_space) {
    case model::CollisionSpaceKind::kSimple:
      space_ = dSimpleSpaceCreate(nullptr);
      break;
    case model::CollisionSpaceKind::kHash:
      space_ = dHashSpaceCreate(nullptr);
      break;
    case model::CollisionSpaceKind::kQuadTree: {
      const dVector3 center = {0, 0, 0, 0};
      const dVector3 extents = {500, 500, 500, 0};
      space_ = dQuadTreeSpaceCreate(nullptr, center, extents, 6);
      break;
    }
  }
  contacts_ = dJointGroupCreate(0);
  contact_buffer_.resize(static_cast<size_t>(params.maxContacts));

  auto add_geom_info = [this](dGeomID geom, int body, int owner, const std::string& material) {
    GeomInfo info{body, owner, Surface(material), Eigen::Vector3d::Zero(), false};
    if (owner >= 0) {
      // The geom frame is the body frame (geoms are only offset, never
      // turned), where the spin axis is fixed.
      const model::FlatBody& flat = model_.bodies[static_cast<size_t>(owner)];
      const std::vector<model::Joint>& joints =
          flat.robot < 0 ? model_.world->joints
                         : model_.world->robots[static_cast<size_t>(flat.robot)].robot.joints;
      if (const std::optional<Eigen::Vector3d> axis = model::SpinAxis(*flat.source, joints)) {
        info.spin_axis = *axis;
        info.has_spin_axis = true;
      }
    }
    // A body's own "rolling" material needs its own axis (the loader refuses
    // one without); the ground's means "along the rolling direction of
    // whatever wheel touches it".
    SP_CHECK_MSG(owner < 0 || info.has_spin_axis ||
                     info.surface.friction_direction != model::FrictionDirection::kRolling,
                 "body '" + model::QualifiedBodyName(model_, owner) +
                     "' with a rolling material has no spin axis; the loader should have "
                     "refused it");
    geom_info_.push_back(info);
    dGeomSetData(geom, reinterpret_cast<void*>(static_cast<uintptr_t>(geom_info_.size())));
  };

  if (world.has_plane) {
    const dGeomID plane =
        dCreatePlane(space_, world.plane[0], world.plane[1], world.plane[2], world.plane[3]);
    add_geom_info(plane, -1, -1, world.plane_material);
    const model::Material* material =
        world.plane_material.empty() ? nullptr : world.FindMaterial(world.plane_material);
    if (material != nullptr && material->soil) {
      soil_ = std::make_unique<OdeSoil>(params_);
      soil_->AddGround(plane, *material->soil);
    }
  }
  if (world.heightfield) {
    const model::Heightfield& h = *world.heightfield;
    heightfield_data_ = dGeomHeightfieldDataCreate();
    dGeomHeightfieldDataBuildDouble(heightfield_data_, h.samples.data(), 1, h.width, h.depth,
                                    h.columns, h.rows, h.scale, h.offset, h.thickness, 0);
    const dGeomID field = dCreateHeightfield(space_, heightfield_data_, 1);
    // ODE's heightfield is y-up; turned so that its y follows "up".
    heightfield_pose_ = world.HeightfieldPose();
    dGeomSetPosition(field, h.position.x(), h.position.y(), h.position.z());
    dMatrix3 rotation;
    ToOde(heightfield_pose_.linear(), rotation);
    dGeomSetRotation(field, rotation);
    heightfield_geom_ = field;
    add_geom_info(field, -1, -1, h.material);
    const model::Material* material = h.material.empty() ? nullptr : world.FindMaterial(h.material);
    if (material != nullptr && material->soil) {
      if (!soil_) soil_ = std::make_unique<OdeSoil>(params_);
      soil_->AddHeightfield(field, *material->soil, h, heightfield_pose_);
    }
  }

  // Bodies: ODE puts the body origin at the centre of mass, so the geometry
  // is offset by -com in the body frame.
  bodies_.resize(model.bodies.size());
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const model::FlatBody& flat = model.bodies[i];
    const model::Body& src = *flat.source;
    Body& body = bodies_[i];
    building_body_ = static_cast<int>(i);
    body.com = src.com;
    const model::Geometry& g = src.geometry;
    switch (g.kind) {
      case model::GeometryKind::kNone: break;
      case model::GeometryKind::kBox:
        body.geom = dCreateBox(space_, g.size.x(), g.size.y(), g.size.z());
        break;
      case model::GeometryKind::kSphere: body.geom = dCreateSphere(space_, g.size.x()); break;
      case model::GeometryKind::kCylinder:
        body.geom = dCreateCylinder(space_, g.size.x(), g.size.y());
        break;
      case model::GeometryKind::kCapsule:
        body.geom = dCreateCapsule(space_, g.size.x(), g.size.y());
        break;
    }
    dMatrix3 rotation;
    ToOde(flat.pose.linear(), rotation);
    if (src.is_static) {
      SP_CHECK(body.geom != nullptr);
      dGeomSetPosition(body.geom, flat.pose.translation().x(), flat.pose.translation().y(),
                       flat.pose.translation().z());
      dGeomSetRotation(body.geom, rotation);
      add_geom_info(body.geom, -1, static_cast<int>(i), src.material);
      continue;
    }
    body.body = dBodyCreate(world_);
    dMass mass;
    const Eigen::Matrix3d& inertia = src.inertia;
    dMassSetParameters(&mass, src.mass, 0, 0, 0, inertia(0, 0), inertia(1, 1), inertia(2, 2),
                       inertia(0, 1), inertia(0, 2), inertia(1, 2));
    dBodySetMass(body.body, &mass);
    const Eigen::Vector3d com_world = flat.pose * src.com;
    dBodySetPosition(body.body, com_world.x(), com_world.y(), com_world.z());
    dBodySetRotation(body.body, rotation);
    // Velocities in files are of the body frame origin; ODE's are of the com.
    const Eigen::Vector3d v_com =
        flat.linear_velocity + flat.angular_velocity.cross(com_world - flat.pose.translation());
    dBodySetLinearVel(body.body, v_com.x(), v_com.y(), v_com.z());
    dBodySetAngularVel(body.body, flat.angular_velocity.x(), flat.angular_velocity.y(),
                       flat.angular_velocity.z());
    dBodySetData(body.body, reinterpret_cast<void*>(static_cast<uintptr_t>(i + 1)));
    if (body.geom != nullptr) {
      dGeomSetBody(body.geom, body.body);
      if (!src.com.isZero()) dGeomSetOffsetPosition(body.geom, -src.com.x(), -src.com.y(), -src.com.z());
      add_geom_info(body.geom, static_cast<int>(i), static_cast<int>(i), src.material);
    }
  }

  building_body_ = -1;
  // Joints, created in the initial pose so that ODE's zero angles are the
  // pose of the files.
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const model::FlatJoint& flat = model.joints[j];
    auto joint = std::make_unique<Joint>();
    joint->kind = flat.source->kind;
    dJointID id = nullptr;
    switch (joint->kind) {
      case model::JointKind::kFixed: id = dJointCreateFixed(world_, nullptr); break;
      case model::JointKind::kHinge: id = dJointCreateHinge(world_, nullptr); break;
      case model::JointKind::kSlider: id = dJointCreateSlider(world_, nullptr); break;
      case model::JointKind::kBall: id = dJointCreateBall(world_, nullptr); break;
      case model::JointKind::kUniversal: id = dJointCreateUniversal(world_, nullptr); break;
      case model::JointKind::kHinge2: id = dJointCreateHinge2(world_, nullptr); break;
    }
    auto body_of = [this](int index) -> dBodyID {
      return index < 0 ? nullptr : bodies_[static_cast<size_t>(index)].body;
    };
    dJointAttach(id, body_of(flat.body1), body_of(flat.body2));
    const Eigen::Vector3d& a = flat.anchor;
    const Eigen::Vector3d& x1 = flat.axis[0];
    const Eigen::Vector3d& x2 = flat.axis[1];
    switch (joint->kind) {
      case model::JointKind::kFixed: dJointSetFixed(id); break;
      case model::JointKind::kHinge:
        dJointSetHingeAnchor(id, a.x(), a.y(), a.z());
        dJointSetHingeAxis(id, x1.x(), x1.y(), x1.z());
        break;
      case model::JointKind::kSlider: dJointSetSliderAxis(id, x1.x(), x1.y(), x1.z()); break;
      case model::JointKind::kBall: dJointSetBallAnchor(id, a.x(), a.y(), a.z()); break;
      case model::JointKind::kUniversal:
        dJointSetUniversalAnchor(id, a.x(), a.y(), a.z());
        dJointSetUniversalAxis1(id, x1.x(), x1.y(), x1.z());
        dJointSetUniversalAxis2(id, x2.x(), x2.y(), x2.z());
        break;
      case model::JointKind::kHinge2: {
        dJointSetHinge2Anchor(id, a.x(), a.y(), a.z());
        const dReal axis1[3] = {x1.x(), x1.y(), x1.z()};
        const dReal axis2[3] = {x2.x(), x2.y(), x2.z()};
        dJointSetHinge2Axes(id, axis1, axis2);
        break;
      }
    }
    joint->joint = id;
    dJointSetFeedback(id, &joint->feedback);
    joints_.push_back(std::move(joint));
    // The motor rows' softness: a velocity per force (their stops keep the
    // world's spring law, which ODE copied at creation).
    for (int axis = 0; axis < flat.num_axes; ++axis)
      SetJointParam(static_cast<int>(j), dParamCFM + dParamGroup * axis, params.MotorCFM());
  }
  SetStopsOfTheFiles(model, this);
  contact_force_.assign(bodies_.size(), Eigen::Vector3d::Zero());
  contact_torque_.assign(bodies_.size(), Eigen::Vector3d::Zero());
  ray_ = dCreateRay(nullptr, 1.0);
}

OdeWorld::~OdeWorld() {
  // A dead world is abandoned: ODE's destroy functions would trip its own
  // assertions on what the failed call left (a locked space, queued jobs).
  if (dead_) return;
  if (ray_ != nullptr) dGeomDestroy(ray_);
  dJointGroupDestroy(contacts_);
  dSpaceDestroy(space_);  // destroys the geoms it holds (cleanup mode on)
  dWorldDestroy(world_);  // destroys bodies and joints
  if (heightfield_data_ != nullptr) dGeomHeightfieldDataDestroy(heightfield_data_);
  dThreadingFreeImplementation(threading_);
}

std::vector<std::string> OdeWorld::SuspectBodies() const {
  std::vector<BodyState> moving;
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const dBodyID b = bodies_[i].body;
    if (b == nullptr) continue;
    BodyState state;
    state.body = static_cast<int>(i);
    state.position = FromOde(dBodyGetPosition(b));
    const dReal* q = dBodyGetQuaternion(b);
    state.orientation = Eigen::Vector4d(q[0], q[1], q[2], q[3]);
    state.linear_velocity = FromOde(dBodyGetLinearVel(b));
    state.angular_velocity = FromOde(dBodyGetAngularVel(b));
    moving.push_back(state);
  }
  return sim::SuspectBodies(model_, moving);
}

OdeError OdeWorld::Fail(const OdeError& raised, const std::string& during) {
  dead_ = true;
  return OdeError(raised.ode_message(), during, SuspectBodies());
}

model::SurfaceProperties OdeWorld::Surface(const std::string& material) const {
  if (material.empty()) return model::ResolveSurface(nullptr, params_);
  const model::Material* m = model_.world->FindMaterial(material);
  SP_CHECK_MSG(m != nullptr, "material '" + material + "' was not checked by the loader");
  return model::ResolveSurface(m, params_);
}

dJointFeedback* OdeWorld::NextFeedback() {
  const size_t chunk = feedback_used_ / kFeedbackChunk;
  if (chunk == feedback_chunks_.size())
    feedback_chunks_.push_back(std::make_unique<dJointFeedback[]>(kFeedbackChunk));
  dJointFeedback* feedback = &feedback_chunks_[chunk][feedback_used_ % kFeedbackChunk];
  ++feedback_used_;
  return feedback;
}

void OdeWorld::NearCallback(void* data, dGeomID o1, dGeomID o2) {
  static_cast<OdeWorld*>(data)->Collide(o1, o2);
}

void OdeWorld::Collide(dGeomID o1, dGeomID o2) {
  // The moving body goes first: ODE would store a joint attached to
  // (null, body) swapped, with that body's feedback in f1, so keeping the
  // order explicit keeps the feedback bookkeeping simple.
  if (dGeomGetBody(o1) == nullptr) std::swap(o1, o2);
  const dBodyID b1 = dGeomGetBody(o1);
  const dBodyID b2 = dGeomGetBody(o2);
  if (b1 == nullptr) return;  // static against static
  if (b1 != nullptr && b2 != nullptr && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
  if (soil_ && soil_->IsGround(o2) && CollideWithSoil(o1, b1, o2)) return;
  const int n = dCollide(o1, o2, static_cast<int>(contact_buffer_.size()),
                         &contact_buffer_[0].geom, sizeof(dContact));
  if (n <= 0) return;
  const GeomInfo& g1 = geom_info_[reinterpret_cast<uintptr_t>(dGeomGetData(o1)) - 1];
  const GeomInfo& g2 = geom_info_[reinterpret_cast<uintptr_t>(dGeomGetData(o2)) - 1];
  const model::SurfaceProperties combined = model::CombineSurfaces(g1.surface, g2.surface);
  dSurfaceParameters surface{};
  // Slip1/Slip2 give the friction rows their own compliance (velocity per
  // force, as ODE's CFM is, so the same at any step); without them the
  // world CFM, meant for joints, let a cornering wheel creep sideways.
  surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM | dContactSlip1 |
                 dContactSlip2;
  surface.mu = combined.mu;
  surface.slip1 = params_.contactSlip;
  surface.slip2 = params_.contactSlip;
  surface.soft_erp = combined.soft_erp;
  // A physical stiffness and damping are those of the whole contact: its n
  // points share them (k/n, c/n each), which keeps ERP and multiplies CFM
  // by n. Per-step softness stays per point, as it always was.
  surface.soft_cfm = combined.HasStiffness() ? combined.soft_cfm * n : combined.soft_cfm;
  if (combined.bounce > 0.0) {
    surface.mode |= dContactBounce;
    surface.bounce = combined.bounce;
    surface.bounce_vel = combined.bounce_velocity;
  }
  const double rolling = combined.rolling_friction;
  if (rolling > 0.0) {
    surface.mode |= dContactRolling;
    surface.rho = rolling;
    surface.rho2 = rolling;
    surface.rhoN = 0.0;
  }
  // What one step of this pair's friction can take off a slip (the cone,
  // below): the pair's, so looked up once, for its first sliding point.
  double one_step_stops = -1.0;
  const auto slip_one_step_stops = [&] {
    if (one_step_stops < 0.0)
      one_step_stops = combined.mu * params_.stepsize * LoadPerMass(o1, b1, o2, b2);
    return one_step_stops;
  };
  for (int i = 0; i < n; ++i) {
    dContact& contact = contact_buffer_[static_cast<size_t>(i)];
    contact.surface = surface;
    // ODE's friction pyramid bounds each of two tangent directions
    // separately, mu N along fdir1 and mu2 N along fdir2 = normal x fdir1.
    // Left to ODE, the directions come from the normal alone (world x and
    // z on a y-up plane), so friction depended on the heading: a cube
    // sliding at 45 degrees braked at sqrt(2) mu g. A wheel's contact
    // takes its rolling direction (mu along it, mu2 across); any other
    // is isotropic Coulomb, mu N against the slip (the cone). mu2 is read
    // across a rolling direction only: across a slip's own direction it
    // would act only while sticking, where a slip has none, and held a
    // slide from turning (materials say so at load, docs/contacts.md).
    const Eigen::Vector3d normal = FromOde(contact.geom.normal);
    const std::optional<Eigen::Vector3d> rolling_direction =
        RollingDirection(combined, normal, WorldSpinAxis(g1, o1), WorldSpinAxis(g2, o2));
    const std::optional<Eigen::Vector3d> slip_direction =
        rolling_direction ? std::nullopt : SlipDirection(SlipVelocity(o1, o2, contact.geom));
    const bool rolls = rolling_direction.has_value(), slides = slip_direction.has_value();
    const Eigen::Vector3d direction =
        rolls ? *rolling_direction : slides ? *slip_direction : Eigen::Vector3d::Zero();
    // Looked up only where it is used: a slow slide, or a sticking contact.
    const auto last = [&] { return NearestLastContact(o1, o2, FromOde(contact.geom.pos)); };
    if (rolls || slides) {
      contact.surface.mode |= dContactFDir1;
      contact.fdir1[0] = direction.x();
      contact.fdir1[1] = direction.y();
      contact.fdir1[2] = direction.z();
      if (rolls && combined.mu2 != combined.mu) {
        contact.surface.mode |= dContactMu2;
        contact.surface.mu2 = combined.mu2;
      } else if (slides) {
        // Isotropic Coulomb: a sliding contact's force is mu N against the
        // slip (the cone). A second row holding up to mu N across it (ODE's
        // pyramid) kept a slide from turning, so a skidding vehicle could
        // not drift. Across the slip the cone's force is mu N v_across /
        // |v|, a damping of mu N / |v|:
        // - a slip one step of friction cannot stop (above mu h N / m, N
        //   the pair's last load, m its mass) turns by little in a step,
        //   and the across row is left free (mu2 0);
        // - a slower slip turns within a step (time constant m |v| / mu N),
        //   which an explicit damping overshoots: the across row gets the
        //   damping implicitly, as its compliance (slip2, velocity per
        //   force) |v| / (mu N), N the load of this point at the last
        //   step. A new contact has no load yet and is held across for
        //   that step, as a sticking one is.
        const double slip_speed = SlipVelocity(o1, o2, contact.geom).norm();
        if (slip_speed > slip_one_step_stops()) {
          contact.surface.mode |= dContactMu2;
          contact.surface.mu2 = 0.0;
        } else if (const LastContact* point = last();
                   point != nullptr && point->load > 0.0 && combined.mu > 0.0) {
          contact.surface.slip2 =
              std::max(params_.contactSlip, slip_speed / (combined.mu * point->load));
        }
      }
    } else if (const LastContact* point = rolls ? nullptr : last(); point != nullptr) {
      // Sticking: which way it will slide is not known; the force that
      // holds it is. Its first direction along that force makes the
      // pyramid's mu N the cone's bound on it (with ODE's directions a
      // force at 45 degrees to them held up to sqrt(2) mu N), and the
      // slide it starts is along it.
      const Eigen::Vector3d held = point->friction - point->friction.dot(normal) * normal;
      if (held.norm() > 1e-9 * (1.0 + point->load)) {
        const Eigen::Vector3d along = held.normalized();
        contact.surface.mode |= dContactFDir1;
        contact.fdir1[0] = along.x();
        contact.fdir1[1] = along.y();
        contact.fdir1[2] = along.z();
      }
    }
    // Sticking without a direction or a force: mu holds in every
    // direction (the force that starts a slide is the mu N that then
    // brakes it).
    const dJointID joint = dJointCreateContact(world_, contacts_, &contact);
    dJointAttach(joint, b1, b2);
    dJointFeedback* feedback = NextFeedback();
    dJointSetFeedback(joint, feedback);
    contact_records_.push_back(ContactRecord{g1.body, g2.body, feedback, o1, o2,
                                             FromOde(contact.geom.pos), normal,
                                             rolls ? direction : Eigen::Vector3d::Zero()});
  }
  contact_count_ += n;
}

bool OdeWorld::CollideWithSoil(dGeomID o1, dBodyID b1, dGeomID o2) {
  const GeomInfo& g1 = geom_info_[reinterpret_cast<uintptr_t>(dGeomGetData(o1)) - 1];
  OdeSoil::BodyContact soil;
  if (!soil_->Contact(o1, b1, g1.body, o2, &soil)) return false;  // rigid ground
  if (!soil.contact) return true;  // above the soil
  dContact& contact = *soil.contact;
  const dJointID joint = dJointCreateContact(world_, contacts_, &contact);
  dJointAttach(joint, b1, nullptr);
  dJointFeedback* feedback = NextFeedback();
  dJointSetFeedback(joint, feedback);
  contact_records_.push_back(ContactRecord{g1.body, -1, feedback, o1, o2,
                                           FromOde(contact.geom.pos), FromOde(contact.geom.normal),
                                           Eigen::Vector3d::Zero()});
  ++contact_count_;
  // The soil's plain forces act where the rows say (a wheel's centre, a
  // plate's centroid of pressure).
  const Eigen::Vector3d& at = soil.at;
  dBodyAddForceAtPos(b1, soil.force.x(), soil.force.y(), soil.force.z(), at.x(), at.y(), at.z());
  dBodyAddTorque(b1, soil.torque.x(), soil.torque.y(), soil.torque.z());
  const Eigen::Vector3d com = FromOde(dBodyGetPosition(b1));
  soil_pushes_.push_back(SoilPush{g1.body, soil.force, soil.torque + (at - com).cross(soil.force),
                                  soil.rows, feedback});
  return true;
}

std::optional<Eigen::Vector3d> OdeWorld::WorldSpinAxis(const GeomInfo& info,
                                                       dGeomID geom) const {
  if (!info.has_spin_axis) return std::nullopt;
  const dReal* r = dGeomGetRotation(geom);
  Eigen::Vector3d axis;
  for (int row = 0; row < 3; ++row)
    axis[row] = r[row * 4] * info.spin_axis.x() + r[row * 4 + 1] * info.spin_axis.y() +
                r[row * 4 + 2] * info.spin_axis.z();
  return axis;
}

Eigen::Vector3d OdeWorld::SlipVelocity(dGeomID o1, dGeomID o2, const dContactGeom& contact) const {
  const Eigen::Vector3d normal = FromOde(contact.normal);
  const dBodyID b1 = dGeomGetBody(o1);
  const dBodyID b2 = dGeomGetBody(o2);
  dVector3 v1 = {0, 0, 0, 0}, v2 = {0, 0, 0, 0};
  if (b1 != nullptr) dBodyGetPointVel(b1, contact.pos[0], contact.pos[1], contact.pos[2], v1);
  if (b2 != nullptr) dBodyGetPointVel(b2, contact.pos[0], contact.pos[1], contact.pos[2], v2);
  Eigen::Vector3d slip = FromOde(v1) - FromOde(v2);
  slip -= slip.dot(normal) * normal;
  return slip;
}

std::vector<ContactReadout> OdeWorld::ReadContacts() const {
  std::vector<ContactReadout> out;
  out.reserve(contact_records_.size());
  for (const ContactRecord& record : contact_records_)
    out.push_back(ContactReadout{record.body1, record.body2, record.position, record.normal,
                                 record.rolling});
  return out;
}

void OdeWorld::BareNearCallback(void* data, dGeomID o1, dGeomID o2) {
  auto* self = static_cast<OdeWorld*>(data);
  const dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
  if (b1 == nullptr && b2 == nullptr) return;
  if (b1 != nullptr && b2 != nullptr && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
  std::vector<dContact>& contacts = self->contact_buffer_;
  const int n = dCollide(o1, o2, static_cast<int>(contacts.size()), &contacts[0].geom,
                         sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    dContact& contact = contacts[static_cast<size_t>(i)];
    contact.surface = dSurfaceParameters{};
    contact.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
    contact.surface.mu = self->params_.contactMu;
    contact.surface.soft_erp = 0.2;
    contact.surface.soft_cfm = 1e-5;
    dJointAttach(dJointCreateContact(self->world_, self->contacts_, &contact), b1, b2);
  }
}

void OdeWorld::BareStep() {
  dSpaceCollide(space_, this, &OdeWorld::BareNearCallback);
  if (params_.stepper == "quick") dWorldQuickStep(world_, params_.stepsize);
  else dWorldStep(world_, params_.stepsize);
  dJointGroupEmpty(contacts_);
}

void OdeWorld::Step() {
  if (dead_)
    throw OdeError("the world failed in an earlier step and cannot go on", "step",
                   SuspectBodies());
  // Messages of the construction are reported with the first step.
  if (!first_step_) messages_.clear();
  first_step_ = false;
  contact_records_.clear();
  soil_pushes_.clear();
  feedback_used_ = 0;
  contact_count_ = 0;
  {
    const MessageSinkScope sink(&messages_);
    try {
      dSpaceCollide(space_, this, &OdeWorld::NearCallback);
    } catch (const OdeError& e) {
      throw Fail(e, "collision");
    } catch (...) {
      dead_ = true;  // our own callback threw: the space stays locked
      throw;
    }
    try {
      if (params_.stepper == "quick") {
        dWorldQuickStep(world_, params_.stepsize);
      } else {
        dWorldStep(world_, params_.stepsize);
      }
    } catch (const OdeError& e) {
      throw Fail(e, "step");
    }
  }
  if (soil_) {
    for (const SoilPush& push : soil_pushes_) soil_->RowForce(push.rows, FromOde(push.feedback->f1));
    soil_->AfterStep(&messages_);
  }
  for (size_t i = 0; i < bodies_.size(); ++i) {
    contact_force_[i].setZero();
    contact_torque_[i].setZero();
  }
  for (const SoilPush& push : soil_pushes_) {
    contact_force_[static_cast<size_t>(push.body)] += push.force;
    contact_torque_[static_cast<size_t>(push.body)] += push.torque;
  }
  for (const ContactRecord& record : contact_records_) {
    if (record.body1 >= 0) {
      contact_force_[record.body1] += FromOde(record.feedback->f1);
      contact_torque_[record.body1] += FromOde(record.feedback->t1);
    }
    if (record.body2 >= 0) {
      contact_force_[record.body2] += FromOde(record.feedback->f2);
      contact_torque_[record.body2] += FromOde(record.feedback->t2);
    }
  }
  RecordLastContacts();
  dJointGroupEmpty(contacts_);
  TrackContinuousAngles(false);
}

void OdeWorld::RecordLastContacts() {
  last_contacts_.clear();
  for (const ContactRecord& record : contact_records_) {
    // geom1 has the body; the normal points into it (ODE: moving geom1
    // along the normal by the depth separates them), so its load is f1.n.
    const Eigen::Vector3d force = FromOde(record.feedback->f1);
    const double load = force.dot(record.normal);
    last_contacts_.push_back(LastContact{record.geom1, record.geom2, record.position,
                                         std::max(0.0, load), force - load * record.normal});
  }
  std::stable_sort(last_contacts_.begin(), last_contacts_.end(),
                   [](const LastContact& a, const LastContact& b) {
                     return GeomPairBefore(a.geom1, a.geom2, b.geom1, b.geom2);
                   });
}

std::pair<const OdeWorld::LastContact*, const OdeWorld::LastContact*> OdeWorld::LastContactsOf(
    dGeomID geom1, dGeomID geom2) const {
  const auto first = std::lower_bound(
      last_contacts_.begin(), last_contacts_.end(), std::make_pair(geom1, geom2),
      [](const LastContact& a, const std::pair<dGeomID, dGeomID>& pair) {
        return GeomPairBefore(a.geom1, a.geom2, pair.first, pair.second);
      });
  auto end = first;
  while (end != last_contacts_.end() && end->geom1 == geom1 && end->geom2 == geom2) ++end;
  const LastContact* begin = last_contacts_.data() + (first - last_contacts_.begin());
  return {begin, begin + (end - first)};
}

const OdeWorld::LastContact* OdeWorld::NearestLastContact(dGeomID geom1, dGeomID geom2,
                                                          const Eigen::Vector3d& position) const {
  const auto [begin, end] = LastContactsOf(geom1, geom2);
  const LastContact* nearest = nullptr;
  for (const LastContact* it = begin; it != end; ++it) {
    if (nearest == nullptr ||
        (it->position - position).squaredNorm() < (nearest->position - position).squaredNorm())
      nearest = it;
  }
  return nearest;
}

double OdeWorld::LoadPerMass(dGeomID geom1, dBodyID b1, dGeomID geom2, dBodyID b2) const {
  const auto [begin, end] = LastContactsOf(geom1, geom2);
  double load = 0.0;
  for (const LastContact* it = begin; it != end; ++it) load += it->load;
  if (load <= 0.0) return gravity_;  // a new contact: its weight is all it is known to carry
  double inverse_mass = 0.0;
  for (const dBodyID b : {b1, b2}) {
    if (b == nullptr) continue;
    dMass mass;
    dBodyGetMass(b, &mass);
    inverse_mass += 1.0 / mass.mass;
  }
  return load * inverse_mass;
}

void OdeWorld::TrackContinuousAngles(bool first) {
  constexpr double kPi = 3.14159265358979323846;
  for (size_t j = 0; j < joints_.size(); ++j) {
    Joint& joint = *joints_[j];
    const int axes = model_.joints[j].num_axes;
    const bool rotational = joint.kind == model::JointKind::kHinge ||
                            joint.kind == model::JointKind::kUniversal ||
                            joint.kind == model::JointKind::kHinge2;
    for (int a = 0; a < axes && a < 3; ++a) {
      const double now = JointPosition(static_cast<int>(j), a);
      if (first || !rotational) {
        joint.continuous[a] = now;
      } else {
        // ODE's angle is in [-pi, pi]: the change is the shortest way round.
        double change = now - joint.wrapped[a];
        if (change > kPi) change -= 2 * kPi;
        else if (change < -kPi) change += 2 * kPi;
        joint.continuous[a] += change;
      }
      joint.wrapped[a] = now;
    }
  }
}

std::vector<WheelSoilReadout> OdeWorld::ReadWheelSoil() const {
  if (!soil_) return {};
  return soil_->LastStep();
}

BodyReadout OdeWorld::ReadBody(int index) const {
  const Body& body = bodies_[static_cast<size_t>(index)];
  BodyReadout out;
  out.contact_force = contact_force_[static_cast<size_t>(index)];
  out.contact_torque = contact_torque_[static_cast<size_t>(index)];
  if (body.body == nullptr) {
    const model::FlatBody& flat = model_.bodies[static_cast<size_t>(index)];
    out.position = flat.pose.translation();
    out.orientation = Eigen::Quaterniond(flat.pose.linear());
    out.linear_velocity.setZero();
    out.angular_velocity.setZero();
    return out;
  }
  const dReal* q = dBodyGetQuaternion(body.body);
  out.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  const Eigen::Vector3d com_world = FromOde(dBodyGetPosition(body.body));
  const Eigen::Vector3d offset = out.orientation * body.com;
  out.position = com_world - offset;
  out.angular_velocity = FromOde(dBodyGetAngularVel(body.body));
  out.linear_velocity = FromOde(dBodyGetLinearVel(body.body)) - out.angular_velocity.cross(offset);
  return out;
}

double OdeWorld::JointPosition(int joint, int axis) const {
  const dJointID id = joints_[static_cast<size_t>(joint)]->joint;
  switch (joints_[static_cast<size_t>(joint)]->kind) {
    case model::JointKind::kHinge: return dJointGetHingeAngle(id);
    case model::JointKind::kSlider: return dJointGetSliderPosition(id);
    case model::JointKind::kUniversal:
      return axis == 0 ? dJointGetUniversalAngle1(id) : dJointGetUniversalAngle2(id);
    case model::JointKind::kHinge2:
      return axis == 0 ? dJointGetHinge2Angle1(id) : dJointGetHinge2Angle2(id);
    default: return 0.0;
  }
}

double OdeWorld::JointRate(int joint, int axis) const {
  const dJointID id = joints_[static_cast<size_t>(joint)]->joint;
  switch (joints_[static_cast<size_t>(joint)]->kind) {
    case model::JointKind::kHinge: return dJointGetHingeAngleRate(id);
    case model::JointKind::kSlider: return dJointGetSliderPositionRate(id);
    case model::JointKind::kUniversal:
      return axis == 0 ? dJointGetUniversalAngle1Rate(id) : dJointGetUniversalAngle2Rate(id);
    case model::JointKind::kHinge2:
      return axis == 0 ? dJointGetHinge2Angle1Rate(id) : dJointGetHinge2Angle2Rate(id);
    default: return 0.0;
  }
}

JointReadout OdeWorld::ReadJoint(int index) const {
  const Joint& joint = *joints_[static_cast<size_t>(index)];
  const int axes = model_.joints[static_cast<size_t>(index)].num_axes;
  JointReadout out;
  for (int a = 0; a < axes; ++a) {
    out.position[a] = JointPosition(index, a);
    out.continuous_position[a] = joint.continuous[a];
    out.rate[a] = JointRate(index, a);
  }
  dVector3 anchor = {0, 0, 0, 0}, anchor2 = {0, 0, 0, 0};
  bool has_anchor2 = true;
  switch (joint.kind) {
    case model::JointKind::kHinge:
      dJointGetHingeAnchor(joint.joint, anchor);
      dJointGetHingeAnchor2(joint.joint, anchor2);
      break;
    case model::JointKind::kBall:
      dJointGetBallAnchor(joint.joint, anchor);
      dJointGetBallAnchor2(joint.joint, anchor2);
      break;
    case model::JointKind::kUniversal:
      dJointGetUniversalAnchor(joint.joint, anchor);
      dJointGetUniversalAnchor2(joint.joint, anchor2);
      break;
    case model::JointKind::kHinge2:
      dJointGetHinge2Anchor(joint.joint, anchor);
      dJointGetHinge2Anchor2(joint.joint, anchor2);
      break;
    case model::JointKind::kFixed:
    case model::JointKind::kSlider: {
      has_anchor2 = false;  // no anchor: the first body's origin stands for it
      const dBodyID b = dJointGetBody(joint.joint, 0);
      if (b != nullptr) {
        const dReal* p = dBodyGetPosition(b);
        anchor[0] = p[0];
        anchor[1] = p[1];
        anchor[2] = p[2];
      }
      break;
    }
  }
  out.anchor = FromOde(anchor);
  if (has_anchor2) out.anchor_error = (FromOde(anchor2) - out.anchor).norm();
  const model::FlatJoint& flat = model_.joints[static_cast<size_t>(index)];
  if (flat.body1 < 0 && flat.body2 >= 0) {
    // Attached as (world, body): ODE swapped it to (body, world), so the
    // force on body2 is in f1/t1 and the world takes the rest.
    out.force2 = FromOde(joint.feedback.f1);
    out.torque2 = FromOde(joint.feedback.t1);
  } else {
    out.force1 = FromOde(joint.feedback.f1);
    out.torque1 = FromOde(joint.feedback.t1);
    out.force2 = FromOde(joint.feedback.f2);
    out.torque2 = FromOde(joint.feedback.t2);
  }
  return out;
}

void OdeWorld::SetJointParam(int joint, int parameter, double value) {
  const dJointID id = joints_[static_cast<size_t>(joint)]->joint;
  switch (joints_[static_cast<size_t>(joint)]->kind) {
    case model::JointKind::kHinge: dJointSetHingeParam(id, parameter, value); break;
    case model::JointKind::kSlider: dJointSetSliderParam(id, parameter, value); break;
    case model::JointKind::kUniversal: dJointSetUniversalParam(id, parameter, value); break;
    case model::JointKind::kHinge2: dJointSetHinge2Param(id, parameter, value); break;
    default: SP_CHECK_MSG(false, "joint kind has no motor or stops");
  }
}

void OdeWorld::ZeroVelocities() {
  for (const Body& body : bodies_) {
    if (body.body == nullptr) continue;
    dBodySetLinearVel(body.body, 0, 0, 0);
    dBodySetAngularVel(body.body, 0, 0, 0);
  }
}

void OdeWorld::AddForce(int body, const Eigen::Vector3d& force) {
  const dBodyID id = bodies_[static_cast<size_t>(body)].body;
  if (id != nullptr) dBodyAddForce(id, force.x(), force.y(), force.z());
}

void OdeWorld::SetMotor(int joint, int axis, double velocity, double max_force) {
  SetJointParam(joint, dParamVel + dParamGroup * axis, velocity);
  SetJointParam(joint, dParamFMax + dParamGroup * axis, max_force);
}

void OdeWorld::SetStops(int joint, int axis, double lo, double hi) {
  // ODE ignores a low stop above the high one, so open both first.
  const double inf = dInfinity;
  SetJointParam(joint, dParamLoStop + dParamGroup * axis, -inf);
  SetJointParam(joint, dParamHiStop + dParamGroup * axis, inf);
  SetJointParam(joint, dParamHiStop + dParamGroup * axis, std::isfinite(hi) ? hi : inf);
  SetJointParam(joint, dParamLoStop + dParamGroup * axis, std::isfinite(lo) ? lo : -inf);
}

double OdeWorld::CastRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         double range, int exclude_body) {
  if (dead_) return range;
  try {
    return CastRayUnguarded(origin, direction, range, exclude_body);
  } catch (const OdeError& e) {
    throw Fail(e, "a scanner ray");
  }
}

double OdeWorld::CastRayUnguarded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                  double range, int exclude_body) {
  dGeomRaySetLength(ray_, range);
  dGeomRaySet(ray_, origin.x(), origin.y(), origin.z(), direction.x(), direction.y(),
              direction.z());
  ray_exclude_body_ = exclude_body;
  ray_hit_ = range;
  dSpaceCollide2(
      ray_, reinterpret_cast<dGeomID>(space_), this, [](void* data, dGeomID a, dGeomID b) {
        auto* self = static_cast<OdeWorld*>(data);
        const dGeomID other = a == self->ray_ ? b : a;
        const GeomInfo& info = self->geom_info_[reinterpret_cast<uintptr_t>(dGeomGetData(other)) - 1];
        if (info.owner_body >= 0 && info.owner_body == self->ray_exclude_body_) return;
        if (other == self->heightfield_geom_) {
          // ODE's ray test takes every cell in the ray's bounding box.
          dVector3 start, dir;
          dGeomRayGet(self->ray_, start, dir);
          self->ray_hit_ = std::min(
              self->ray_hit_, RayHeightfield(*self->model_.world->heightfield, self->heightfield_pose_,
                                             FromOde(start), FromOde(dir), self->ray_hit_));
          return;
        }
        dContactGeom hit;
        if (dCollide(self->ray_, other, 1, &hit, sizeof(dContactGeom)) > 0)
          self->ray_hit_ = std::min(self->ray_hit_, static_cast<double>(hit.depth));
      });
  return ray_hit_;
}

}  // namespace simpartner::sim
