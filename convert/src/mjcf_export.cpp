#include "simpartner/convert/mjcf_export.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "xml_text.h"
#include "simpartner/convert/urdf_import.h"
#include "simpartner/model/body_tree.h"
#include "simpartner/model/flat_model.h"
#include "simpartner/model/surface.h"

namespace simpartner::convert {
namespace {

std::string Vec(const Eigen::Vector3d& v) {
  auto clean = [](double x) { return std::abs(x) < 1e-15 ? 0.0 : x; };
  return NumberText(clean(v.x())) + " " + NumberText(clean(v.y())) + " " +
         NumberText(clean(v.z()));
}

std::string Quat(const Eigen::Matrix3d& rotation) {
  Eigen::Quaterniond q(rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;
  auto clean = [](double x) { return std::abs(x) < 1e-15 ? 0.0 : x; };
  return NumberText(clean(q.w())) + " " + NumberText(clean(q.x())) + " " +
         NumberText(clean(q.y())) + " " + NumberText(clean(q.z()));
}

// "--" may not appear inside an XML comment.
std::string CommentSafe(std::string text) {
  for (size_t at = text.find("--"); at != std::string::npos; at = text.find("--"))
    text.replace(at, 2, "- -");
  return text;
}

class Writer {
 public:
  Writer(const model::World& world, const Parameters& params, const MjcfGains& gains)
      : world_(world), flat_(model::Flatten(world)), params_(params), gains_(gains),
        c_(YUpToZUp()) {}

  MjcfExport Run();

 private:
  bool Static(int body) const {
    return body < 0 || flat_.bodies[static_cast<size_t>(body)].source->is_static;
  }
  void BuildTree();
  std::string BodyName(int body) const { return names_[static_cast<size_t>(body)]; }
  std::string JointName(int joint) const { return joint_names_[static_cast<size_t>(joint)]; }
  const model::Material* MaterialOf(int body) const;
  std::string GeomAttributes(const model::Geometry& geometry, const model::Material* material);
  std::string ContactAttributes(const model::Material* material);
  void WriteBody(int body, const std::string& indent, std::ostringstream& out);
  Eigen::Isometry3d ZUpPose(int body) const {
    const Eigen::Isometry3d& pose = flat_.bodies[static_cast<size_t>(body)].pose;
    Eigen::Isometry3d z = Eigen::Isometry3d::Identity();
    z.linear() = c_ * pose.linear();
    z.translation() = c_ * pose.translation();
    return z;
  }

  const model::World& world_;
  model::FlatModel flat_;
  const Parameters& params_;
  MjcfGains gains_;
  Eigen::Matrix3d c_;
  std::vector<model::TreeNode> tree_;
  std::vector<std::string> names_;
  std::vector<std::string> joint_names_;
  std::set<int> angle_joints_;          // joints driven by an angle controller (damped)
  std::vector<std::string> not_carried_;
  std::map<double, int> priority_of_mu_;  // lower friction wins: higher priority
  // qvel of the floating roots, in dof order, for the initial keyframe.
  std::vector<double> qvel_;
  bool any_velocity_ = false;
};

const model::Material* Writer::MaterialOf(int body) const {
  const model::FlatBody& flat = flat_.bodies[static_cast<size_t>(body)];
  const std::string& name = flat.source->material;
  if (name.empty()) return nullptr;
  if (flat.robot >= 0) {
    for (const model::Material& m : world_.robots[static_cast<size_t>(flat.robot)].robot.materials)
      if (m.name == name) return &m;
  }
  return world_.FindMaterial(name);
}

void Writer::BuildTree() {
  const model::BodyTree tree = model::BuildBodyTree(flat_);
  tree_ = tree.nodes;
  for (int j : tree.loop_joints)
    not_carried_.push_back("joint '" + JointName(j) +
                           "' closes a loop of bodies; MuJoCo's body tree has no place for it "
                           "(left out)");
}

std::string Writer::ContactAttributes(const model::Material* material) {
  const model::SurfaceProperties surface = model::ResolveSurface(material, params_);
  std::ostringstream out;
  // MuJoCo takes the larger friction of two geoms unless their priorities
  // differ; ours takes the smaller, so lower friction gets higher priority.
  const int priority = priority_of_mu_.at(surface.mu);
  const bool rolling = surface.rolling_friction > 0;
  // Contact softness: ODE corrects the fraction ERP of the penetration per
  // step, i.e. a time constant h / ERP (MuJoCo wants at least 2 h); a
  // material's physical stiffness k and damping c arrive here as the ERP
  // and CFM they give at this step (h / ERP = h + c / k); its CFM
  // makes the constraint give way like MuJoCo's impedance d = A / (A + R)
  // with R = CFM / h, taken at a 1 kg reference effective mass (A = 1).
  const double h = params_.stepsize;
  const double timeconst = std::max(h / surface.soft_erp, 2 * h);
  const double impedance = std::clamp(1.0 / (1.0 + surface.soft_cfm / h), 0.9, 0.9999);
  out << " friction=\"" << NumberText(surface.mu) << " 0 " << NumberText(surface.rolling_friction)
      << "\" condim=\"" << (rolling ? 6 : 3) << "\" priority=\"" << priority << "\" solref=\""
      << NumberText(timeconst) << " 1\" solimp=\"" << NumberText(impedance) << " "
      << NumberText(impedance) << " 0.001\"";
  return out.str();
}

std::string Writer::GeomAttributes(const model::Geometry& geometry,
                                   const model::Material* material) {
  std::ostringstream out;
  switch (geometry.kind) {
    case model::GeometryKind::kBox:
      out << "type=\"box\" size=\"" << Vec(geometry.size / 2) << "\"";
      break;
    case model::GeometryKind::kSphere:
      out << "type=\"sphere\" size=\"" << NumberText(geometry.size.x()) << "\"";
      break;
    case model::GeometryKind::kCylinder:
    case model::GeometryKind::kCapsule:
      out << "type=\"" << (geometry.kind == model::GeometryKind::kCylinder ? "cylinder" : "capsule")
          << "\" size=\"" << NumberText(geometry.size.x()) << " "
          << NumberText(geometry.size.y() / 2) << "\"";
      break;
    case model::GeometryKind::kNone:
      return "";
  }
  out << ContactAttributes(material);
  return out.str();
}

void Writer::WriteBody(int body, const std::string& indent, std::ostringstream& out) {
  const model::TreeNode& node = tree_[static_cast<size_t>(body)];
  const model::FlatBody& flat = flat_.bodies[static_cast<size_t>(body)];
  const model::Body& source = *flat.source;
  const Eigen::Isometry3d pose = ZUpPose(body);
  const Eigen::Isometry3d relative = node.parent < 0 ? pose : ZUpPose(node.parent).inverse() * pose;
  out << indent << "<body name=\"" << EscapeXml(BodyName(body)) << "\" pos=\""
      << Vec(relative.translation()) << "\" quat=\"" << Quat(relative.linear()) << "\">\n";
  const std::string inner = indent + "  ";
  if (node.free) {
    out << inner << "<freejoint name=\"" << EscapeXml(BodyName(body)) << "_free\"/>\n";
    // qvel of a free joint: linear velocity in the world, angular in the
    // body frame.
    const Eigen::Vector3d v = c_ * flat.linear_velocity;
    const Eigen::Vector3d w = pose.linear().transpose() * (c_ * flat.angular_velocity);
    // The velocity of the body frame origin is MuJoCo's too (its free
    // joint moves the body frame).
    for (int k = 0; k < 3; ++k) qvel_.push_back(v[k]);
    for (int k = 0; k < 3; ++k) qvel_.push_back(w[k]);
    any_velocity_ = any_velocity_ || v.norm() > 0 || w.norm() > 0;
  } else if (node.joint >= 0) {
    const model::FlatJoint& joint = flat_.joints[static_cast<size_t>(node.joint)];
    const model::Joint& spec = *joint.source;
    // MuJoCo's joint value is the child relative to its parent; ours is
    // body1 relative to body2: the axis turns round when body1 is the
    // parent, so both count the same way.
    const double sign = node.joint_reversed ? -1.0 : 1.0;
    const Eigen::Vector3d anchor = pose.inverse() * (c_ * joint.anchor);
    auto axis_local = [&](int a) {
      return Eigen::Vector3d(sign * (pose.linear().transpose() * (c_ * joint.axis[a])));
    };
    auto limit = [&](int a) -> std::string {
      const double lo = spec.lo_stop[a], hi = spec.hi_stop[a];
      if (!std::isfinite(lo) && !std::isfinite(hi)) return "";
      return " limited=\"true\" range=\"" + NumberText(std::isfinite(lo) ? lo : -1e10) + " " +
             NumberText(std::isfinite(hi) ? hi : 1e10) + "\"";
    };
    const std::string damping =
        angle_joints_.count(node.joint) != 0
            ? " damping=\"" + NumberText(gains_.position_damping) + "\""
            : "";
    const std::string name = EscapeXml(JointName(node.joint));
    // Joint velocities start at zero (the keyframe lists every dof).
    const int dofs[] = {0, 1, 1, 3, 2, 2};  // JointKind order
    qvel_.insert(qvel_.end(), static_cast<size_t>(dofs[static_cast<int>(spec.kind)]), 0.0);
    switch (spec.kind) {
      case model::JointKind::kFixed:
        break;  // a body without joints is welded to its parent
      case model::JointKind::kHinge:
      case model::JointKind::kSlider:
        out << inner << "<joint name=\"" << name << "\" type=\""
            << (spec.kind == model::JointKind::kHinge ? "hinge" : "slide") << "\" pos=\""
            << Vec(anchor) << "\" axis=\"" << Vec(axis_local(0)) << "\"" << limit(0) << damping
            << "/>\n";
        break;
      case model::JointKind::kBall:
        out << inner << "<joint name=\"" << name << "\" type=\"ball\" pos=\"" << Vec(anchor)
            << "\"/>\n";
        break;
      case model::JointKind::kUniversal:
      case model::JointKind::kHinge2:
        for (int a = 0; a < 2; ++a)
          out << inner << "<joint name=\"" << name << (a == 0 ? "" : "_axis2")
              << "\" type=\"hinge\" pos=\"" << Vec(anchor) << "\" axis=\"" << Vec(axis_local(a))
              << "\"" << limit(a) << damping << "/>\n";
        break;
    }
  }
  const Eigen::Matrix3d& i = source.inertia;
  out << inner << "<inertial pos=\"" << Vec(source.com) << "\" mass=\"" << NumberText(source.mass)
      << "\" fullinertia=\"" << NumberText(i(0, 0)) << " " << NumberText(i(1, 1)) << " "
      << NumberText(i(2, 2)) << " " << NumberText(i(0, 1)) << " " << NumberText(i(0, 2)) << " "
      << NumberText(i(1, 2)) << "\"/>\n";
  const std::string geom = GeomAttributes(source.geometry, MaterialOf(body));
  if (!geom.empty())
    out << inner << "<geom name=\"" << EscapeXml(BodyName(body)) << "\" " << geom << "/>\n";
  for (int child : node.children) WriteBody(child, inner, out);
  out << indent << "</body>\n";
}

MjcfExport Writer::Run() {
  // Names: ours where they are unique in the world, else "<robot>/<name>".
  std::map<std::string, int> body_count, joint_count;
  for (const model::FlatBody& b : flat_.bodies) ++body_count[b.name];
  for (const model::FlatJoint& j : flat_.joints) ++joint_count[j.name];
  for (const model::FlatBody& b : flat_.bodies)
    names_.push_back(body_count[b.name] > 1 && b.robot >= 0
                         ? world_.robots[static_cast<size_t>(b.robot)].name + "/" + b.name
                         : b.name);
  for (const model::FlatJoint& j : flat_.joints)
    joint_names_.push_back(joint_count[j.name] > 1 && j.robot >= 0
                               ? world_.robots[static_cast<size_t>(j.robot)].name + "/" + j.name
                               : j.name);
  for (const model::FlatActuator& a : flat_.actuators)
    if (a.source->kind == model::ActuatorKind::kAngle && a.joint >= 0) angle_joints_.insert(a.joint);

  // Friction priorities: every friction value in use, the lowest first.
  std::set<double> mus;
  mus.insert(model::ResolveSurface(nullptr, params_).mu);
  auto note_material = [&](const model::Material& m) {
    const model::SurfaceProperties s = model::ResolveSurface(&m, params_);
    mus.insert(s.mu);
    if (s.bounce > 0)
      not_carried_.push_back("material '" + m.name + "': bounce " + NumberText(s.bounce) +
                             " (MuJoCo has no restitution coefficient; contacts are inelastic)");
    // A geom in MuJoCo 2.2 has one sliding friction, and the collision
    // code picks a contact's tangent directions.
    if (s.mu2 != s.mu)
      not_carried_.push_back("material '" + m.name + "': mu2 " + NumberText(s.mu2) +
                             " across the first friction direction (MuJoCo 2.2 has one sliding "
                             "friction per geom and no way to orient it; mu " +
                             NumberText(s.mu) + " is used both ways)");
    if (s.friction_direction == model::FrictionDirection::kRolling)
      not_carried_.push_back("material '" + m.name +
                             "': frictionDirection rolling (MuJoCo orients contact friction "
                             "itself)");
    if (m.soil)
      not_carried_.push_back("material '" + m.name + "': soil '" + m.soil->name +
                             "' (MuJoCo has no soil model: the ground is rigid in the MJCF)");
  };
  for (const model::Material& m : world_.materials) note_material(m);
  for (const model::RobotInstance& r : world_.robots)
    for (const model::Material& m : r.robot.materials) note_material(m);
  int rank = static_cast<int>(mus.size());
  for (double mu : mus) priority_of_mu_[mu] = rank--;

  BuildTree();

  std::ostringstream body;
  for (size_t b = 0; b < flat_.bodies.size(); ++b) {
    if (Static(static_cast<int>(b))) {
      const Eigen::Isometry3d pose = ZUpPose(static_cast<int>(b));
      const std::string geom =
          GeomAttributes(flat_.bodies[b].source->geometry, MaterialOf(static_cast<int>(b)));
      if (!geom.empty())
        body << "    <geom name=\"" << EscapeXml(names_[b]) << "\" pos=\"" << Vec(pose.translation())
             << "\" quat=\"" << Quat(pose.linear()) << "\" " << geom << "/>\n";
    } else if (tree_[b].parent < 0) {
      WriteBody(static_cast<int>(b), "    ", body);
    }
  }

  std::ostringstream actuators;
  for (const model::FlatActuator& a : flat_.actuators) {
    if (a.joint < 0) continue;
    const model::FlatJoint& joint = flat_.joints[static_cast<size_t>(a.joint)];
    const std::string joint_name = JointName(a.joint);
    const std::string force = " ctrllimited=\"false\" forcelimited=\"true\" forcerange=\"" +
                              NumberText(-gains_.force_limit) + " " +
                              NumberText(gains_.force_limit) + "\"";
    for (int axis = 0; axis < joint.num_axes; ++axis) {
      const std::string suffix = axis == 0 ? "" : "_axis2";
      if (a.source->kind == model::ActuatorKind::kAngle)
        actuators << "    <position name=\"" << EscapeXml(a.name + suffix) << "\" joint=\""
                  << EscapeXml(joint_name + suffix) << "\" kp=\"" << NumberText(gains_.position_kp)
                  << "\"" << force << "/>\n";
      else
        actuators << "    <velocity name=\"" << EscapeXml(a.name + suffix) << "\" joint=\""
                  << EscapeXml(joint_name + suffix) << "\" kv=\"" << NumberText(gains_.velocity_kv)
                  << "\"" << force << "/>\n";
    }
    if (joint.num_axes == 0)
      not_carried_.push_back("actuator '" + a.name + "' drives a joint without axes (left out)");
  }

  for (const model::FlatSensor& s : flat_.sensors)
    not_carried_.push_back("sensor '" + s.name + "' (" + model::ToString(s.source->kind) +
                           "): MuJoCo sensors differ; left out");
  if (world_.heightfield)
    not_carried_.push_back("the heightfield (left out; the plane, if any, is kept)");
  not_carried_.push_back(
      "contact combination: ours takes the softer softness of two materials, MuJoCo the one of "
      "the higher priority (here: the lower friction)");
  not_carried_.push_back(
      "the step method (ODE dWorldStep/QuickStep, ERP " + NumberText(params_.JointERP()) +
      ", CFM " + NumberText(params_.JointCFM()) +
      " on joints at this step): MuJoCo's joints are exact in joint coordinates");

  std::ostringstream out;
  out << "<!-- MJCF for MuJoCo 2.2, converted by simpartner-convert from " << CommentSafe(world_.file)
      << ".\n"
      << "     Frames: ours are y-up (x forward, y up, z right), MuJoCo's z-up: world\n"
      << "     positions and directions (x, y, z) became (x, -z, y); each body keeps its\n"
      << "     own axes (box half-sizes, cylinder axis z unchanged). Joint values count\n"
      << "     as ours (body1 relative to body2).\n"
      << "     Contacts: friction \"mu 0 rolling\" (ODE has no torsional friction),\n"
      << "     solref timeconst = step / softERP (at least 2 steps), solimp d = 1 / (1 +\n"
      << "     softCFM / step). Servos: angle controllers -> position kp "
      << NumberText(gains_.position_kp) << " with joint\n"
      << "     damping " << NumberText(gains_.position_damping)
      << ", velocity controllers and linear motors -> velocity kv "
      << NumberText(gains_.velocity_kv) << ", all\n"
      << "     limited to +-" << NumberText(gains_.force_limit)
      << " (our motors reach their target within a step up to that force).\n";
  if (any_velocity_)
    out << "     Initial velocities: keyframe \"initial\" (mj_resetDataKeyframe(m, d, 0)).\n";
  out << "     Not carried over:\n";
  for (const std::string& line : not_carried_) out << "       - " << CommentSafe(line) << "\n";
  out << "-->\n";
  const std::string model_name = world_.name.empty() ? "simpartner" : world_.name;
  out << "<mujoco model=\"" << EscapeXml(model_name) << "\">\n"
      << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
      << "  <option timestep=\"" << NumberText(params_.stepsize) << "\" gravity=\""
      << Vec(c_ * world_.gravity) << "\"/>\n"
      // Looks only, for MuJoCo's own viewer (mujoco-simulate): without a
      // light and a ground texture the robot shows as dark shapes on black.
      << "  <visual><headlight ambient=\"0.4 0.4 0.4\" diffuse=\"0.6 0.6 0.6\"/></visual>\n"
      << "  <asset><texture name=\"grid\" type=\"2d\" builtin=\"checker\" width=\"512\" "
         "height=\"512\" rgb1=\"0.2 0.3 0.4\" rgb2=\"0.3 0.4 0.5\"/>"
         "<material name=\"grid\" texture=\"grid\" texrepeat=\"1 1\" texuniform=\"true\"/>"
         "</asset>\n"
      << "  <worldbody>\n"
      << "    <light name=\"sun\" directional=\"true\" pos=\"0 0 10\" dir=\"0 0 -1\"/>\n";
  if (world_.has_plane) {
    const Eigen::Vector3d normal = c_ * world_.plane.head<3>().normalized();
    const Eigen::Vector3d at = normal * world_.plane[3];
    const model::Material* material = world_.FindMaterial(world_.plane_material);
    out << "    <geom name=\"ground\" type=\"plane\" pos=\"" << Vec(at) << "\" zaxis=\""
        << Vec(normal) << "\" size=\"0 0 1\" material=\"grid\"" << ContactAttributes(material)
        << "/>\n";
  }
  out << body.str() << "  </worldbody>\n";
  if (!actuators.str().empty()) out << "  <actuator>\n" << actuators.str() << "  </actuator>\n";
  if (any_velocity_) {
    out << "  <keyframe>\n    <key name=\"initial\" qvel=\"";
    for (size_t k = 0; k < qvel_.size(); ++k) out << (k ? " " : "") << NumberText(qvel_[k]);
    out << "\"/>\n  </keyframe>\n";
  }
  out << "</mujoco>\n";

  MjcfExport result;
  result.xml = out.str();
  result.not_carried = not_carried_;
  result.body_names = names_;
  return result;
}

}  // namespace

Eigen::Matrix3d YUpToZUp() {
  Eigen::Matrix3d c;
  c << 1, 0, 0,
       0, 0, -1,
       0, 1, 0;
  return c;
}

model::World WorldOfRobot(const model::Robot& robot) {
  model::World world;
  world.name = robot.model_name;
  world.file = robot.file;
  model::RobotInstance instance;
  instance.name = robot.model_name;
  instance.file = robot.file;
  instance.resolved_file = robot.file;
  instance.robot = robot;
  world.robots.push_back(instance);
  return world;
}

MjcfExport ExportMjcf(const model::World& world, const Parameters& params,
                      const MjcfGains& gains) {
  Writer writer(world, params, gains);
  return writer.Run();
}

}  // namespace simpartner::convert
