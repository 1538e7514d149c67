#include <cmath>
#include <tuple>
#include <utility>

#include "message_rules.h"
#include "simpartner/message_checks.h"
#include "simpartner/text.h"

namespace simpartner {
namespace {

using message_rules::kNameBytes;
using message_rules::kPathBytes;
using message_rules::kTextBytes;
using message_rules::MessageRules;

// Simulation.engine is VARCHAR(32) in the logger's schema.
constexpr size_t kEngineBytes = 32;
// Bounds on what a model may ask a reader to build, so that a damaged
// message cannot make it allocate gigabytes or draw a world of 1e300 m.
constexpr int64_t kMaxHeightfieldSamples = 16 * 1024 * 1024;
constexpr double kMaxSize = 1e5;  // [m]

MessageCheck CheckWorld(const model_t& m, const MessageRules& rules) {
  if (m.state_every < 1)
    return rules.Problem(MessageFault::kOutOfRange, "state_every",
                         " = " + std::to_string(m.state_every) + " (must be >= 1)");
  if (!std::isfinite(m.step_size) || m.step_size <= 0)
    return rules.Problem(MessageFault::kOutOfRange, "step_size",
                         " = " + FormatNumber(m.step_size) + " (must be a positive number)");
  if (auto bad = rules.Finite("gravity", m.gravity, 3)) return bad;
  if (auto bad = rules.UnitVector("up", m.up)) return bad;
  if (m.has_plane) {
    if (auto bad = rules.Finite("plane", m.plane, 4)) return bad;
    if (std::hypot(m.plane[0], m.plane[1], m.plane[2]) < 1e-9)
      return rules.Problem(MessageFault::kOutOfRange, "plane", " normal (a, b, c) is zero");
  }
  for (const auto& [field, text, bytes] :
       {std::tuple<const char*, const std::string&, size_t>{"host", m.host, kNameBytes},
        {"sender", m.sender, kNameBytes},
        {"engine", m.engine, kEngineBytes},
        {"world_file", m.world_file, kPathBytes},
        {"world_name", m.world_name, kNameBytes},
        {"parameters", m.parameters, kTextBytes},
        {"plane_material", m.plane_material, kNameBytes}})
    if (auto bad = rules.Text(field, text, bytes)) return bad;
  return std::nullopt;
}

MessageCheck CheckRobots(const model_t& m, const MessageRules& rules) {
  for (size_t i = 0; i < m.robots.size(); ++i) {
    const robot_t& r = m.robots[i];
    const MessageRules at = rules.In("robots", i);
    if (auto bad = at.Text("name", r.name, kNameBytes)) return bad;
    if (auto bad = at.Text("model", r.model, kNameBytes)) return bad;
    if (auto bad = at.Text("file", r.file, kPathBytes)) return bad;
    if (auto bad = at.Finite("total_mass", r.total_mass)) return bad;
  }
  return std::nullopt;
}

MessageCheck CheckMaterials(const model_t& m, const MessageRules& rules) {
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const material_t& mat = m.materials[i];
    const MessageRules at = rules.In("materials", i);
    if (auto bad = at.Text("name", mat.name, kNameBytes)) return bad;
    if (auto bad = at.Text("soil_name", mat.soil_name, kNameBytes)) return bad;
    for (const auto& [field, value] :
         {std::pair<const char*, double>{"mu", mat.mu}, {"mu2", mat.mu2},
          {"bounce", mat.bounce}, {"bounce_velocity", mat.bounce_velocity},
          {"soft_erp", mat.soft_erp}, {"soft_cfm", mat.soft_cfm},
          {"stiffness", mat.stiffness}, {"damping", mat.damping},
          {"rolling_friction", mat.rolling_friction}, {"soil_n", mat.soil_n},
          {"soil_kc", mat.soil_kc}, {"soil_kphi", mat.soil_kphi},
          {"soil_cohesion", mat.soil_cohesion}, {"soil_friction_angle", mat.soil_friction_angle},
          {"soil_shear_modulus", mat.soil_shear_modulus},
          {"soil_unloading_stiffness", mat.soil_unloading_stiffness},
          {"soil_viscosity", mat.soil_viscosity}})
      if (auto bad = at.Finite(field, value)) return bad;
    if (mat.friction_direction != material_t::FRICTION_SLIP &&
        mat.friction_direction != material_t::FRICTION_ROLLING)
      return at.Problem(MessageFault::kUnknownValue, "friction_direction",
                        " = " + std::to_string(mat.friction_direction) +
                            " (FRICTION_SLIP or FRICTION_ROLLING)");
  }
  return std::nullopt;
}

// The sizes a geometry kind uses ({lx, ly, lz}, {radius}, {radius,
// length}), each in (0, kMaxSize]; a capsule's cylinder part may be 0 long.
MessageCheck CheckGeometry(const geometry_t& g, const MessageRules& rules) {
  if (auto bad = rules.Finite("size", g.size, 3)) return bad;
  int sizes = 0;
  switch (g.kind) {
    case geometry_t::KIND_NONE: sizes = 0; break;
    case geometry_t::KIND_BOX: sizes = 3; break;
    case geometry_t::KIND_SPHERE: sizes = 1; break;
    case geometry_t::KIND_CYLINDER:
    case geometry_t::KIND_CAPSULE: sizes = 2; break;
    default:
      return rules.Problem(MessageFault::kUnknownValue, "kind",
                           " = " + std::to_string(g.kind) + " (not a geometry_t.KIND_*)");
  }
  for (int k = 0; k < sizes; ++k) {
    const bool may_be_zero = g.kind == geometry_t::KIND_CAPSULE && k == 1;
    const double v = g.size[k];
    if (v < 0 || (v == 0 && !may_be_zero) || v > kMaxSize)
      return rules.Problem(MessageFault::kOutOfRange, "size[" + std::to_string(k) + "]",
                           " = " + FormatNumber(v) + " (" + (may_be_zero ? "0" : "above 0") +
                               " to " + FormatNumber(kMaxSize) + " m)");
  }
  return std::nullopt;
}

MessageCheck CheckBodies(const model_t& m, const MessageRules& rules) {
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    const body_t& b = m.bodies[i];
    const MessageRules at = rules.In("bodies", i);
    if (auto bad = at.Index("robot", b.robot, m.num_robots, true, "robot")) return bad;
    if (auto bad = at.Text("name", b.name, kNameBytes)) return bad;
    if (auto bad = at.Text("material", b.material, kNameBytes)) return bad;
    if (auto bad = CheckGeometry(b.geometry, at.Nested("geometry"))) return bad;
    if (auto bad = at.Finite("mass", b.mass)) return bad;
    if (auto bad = at.Finite("com", b.com, 3)) return bad;
    if (auto bad = at.Finite("inertia", b.inertia, 6)) return bad;
    if (auto bad = at.Finite("initial_position", b.initial_position, 3)) return bad;
    if (auto bad = at.UnitQuaternion("initial_orientation", b.initial_orientation)) return bad;
  }
  return std::nullopt;
}

MessageCheck CheckJoints(const model_t& m, const MessageRules& rules) {
  for (size_t i = 0; i < m.joints.size(); ++i) {
    const joint_t& j = m.joints[i];
    const MessageRules at = rules.In("joints", i);
    if (auto bad = at.Index("robot", j.robot, m.num_robots, true, "robot")) return bad;
    if (auto bad = at.Index("body1", j.body1, m.num_bodies, true, "body")) return bad;
    if (auto bad = at.Index("body2", j.body2, m.num_bodies, true, "body")) return bad;
    if (auto bad = at.Text("name", j.name, kNameBytes)) return bad;
    if (auto bad = at.Finite("anchor", j.anchor, 3)) return bad;
    for (int a = 0; a < 3; ++a)
      if (auto bad = at.Finite(("axis[" + std::to_string(a) + "]").c_str(), j.axis[a], 3))
        return bad;
    // Stops may be infinite (free), never NaN.
    if (auto bad = at.NotNaN("lo_stop", j.lo_stop, 3)) return bad;
    if (auto bad = at.NotNaN("hi_stop", j.hi_stop, 3)) return bad;
  }
  return std::nullopt;
}

MessageCheck CheckSensors(const model_t& m, const MessageRules& rules) {
  for (size_t i = 0; i < m.sensors.size(); ++i) {
    const sensor_t& s = m.sensors[i];
    const MessageRules at = rules.In("sensors", i);
    if (auto bad = at.Index("robot", s.robot, m.num_robots, true, "robot")) return bad;
    if (auto bad = at.Index("body", s.body, m.num_bodies, true, "body")) return bad;
    if (auto bad = at.Index("joint", s.joint, m.num_joints, true, "joint")) return bad;
    if (auto bad = at.Text("name", s.name, kNameBytes)) return bad;
    if (auto bad = at.Finite("position", s.position, 3)) return bad;
    if (auto bad = at.UnitQuaternion("orientation", s.orientation)) return bad;
    if (auto bad = at.Finite("rate", s.rate)) return bad;
    if (auto bad = at.Finite("params", s.params.data(), s.params.size())) return bad;
  }
  return std::nullopt;
}

MessageCheck CheckActuators(const model_t& m, const MessageRules& rules) {
  for (size_t i = 0; i < m.actuators.size(); ++i) {
    const actuator_t& a = m.actuators[i];
    const MessageRules at = rules.In("actuators", i);
    if (auto bad = at.Index("robot", a.robot, m.num_robots, true, "robot")) return bad;
    if (auto bad = at.Index("joint", a.joint, m.num_joints, true, "joint")) return bad;
    if (auto bad = at.Text("name", a.name, kNameBytes)) return bad;
  }
  return std::nullopt;
}

MessageCheck CheckHeightfield(const heightfield_t& h, const MessageRules& rules) {
  if (!h.present) return std::nullopt;
  if (h.rows < 2 || h.columns < 2)
    return rules.Problem(MessageFault::kOutOfRange, "rows",
                         " = " + std::to_string(h.rows) + ", columns = " +
                             std::to_string(h.columns) + " (at least 2 x 2 samples)");
  const int64_t count = static_cast<int64_t>(h.rows) * h.columns;
  if (count > kMaxHeightfieldSamples)
    return rules.Problem(MessageFault::kOutOfRange, "rows",
                         " x columns = " + std::to_string(count) + " samples (at most " +
                             std::to_string(kMaxHeightfieldSamples) + ")");
  if (h.num_samples != count || static_cast<int64_t>(h.samples.size()) != count)
    return rules.Problem(MessageFault::kCountMismatch, "num_samples",
                         " = " + std::to_string(h.num_samples) + " but rows x columns = " +
                             std::to_string(count));
  for (const auto& [field, v] : {std::pair<const char*, double>{"width", h.width}, {"depth", h.depth}})
    if (!std::isfinite(v) || v <= 0 || v > kMaxSize)
      return rules.Problem(MessageFault::kOutOfRange, field,
                           " = " + FormatNumber(v) + " (above 0 to " + FormatNumber(kMaxSize) + " m)");
  for (const auto& [field, v] : {std::pair<const char*, double>{"scale", h.scale},
                                 {"offset", h.offset}, {"thickness", h.thickness}})
    if (auto bad = rules.Finite(field, v)) return bad;
  if (auto bad = rules.Finite("position", h.position, 3)) return bad;
  if (auto bad = rules.Text("material", h.material, kNameBytes)) return bad;
  for (size_t k = 0; k < h.samples.size(); ++k)
    if (!std::isfinite(h.samples[k]))
      return rules.Problem(MessageFault::kNonFinite, "samples[" + std::to_string(k) + "]",
                           " = " + FormatNumber(h.samples[k]));
  return std::nullopt;
}

}  // namespace

MessageCheck CheckModel(const model_t& model) {
  const MessageRules rules("model_t");
  for (auto check : {CheckWorld, CheckRobots, CheckMaterials, CheckBodies, CheckJoints,
                     CheckSensors, CheckActuators})
    if (auto bad = check(model, rules)) return bad;
  return CheckHeightfield(model.heightfield, rules.Nested("heightfield"));
}

ModelOutline OutlineOf(const model_t& model) {
  ModelOutline outline;
  outline.simulation_id = model.simulation_id;
  outline.bodies = model.num_bodies;
  outline.joints = model.num_joints;
  outline.sensors.reserve(model.sensors.size());
  for (const sensor_t& s : model.sensors) outline.sensors.push_back({s.kind, s.name});
  return outline;
}

}  // namespace simpartner
