#include "mujoco_mjcf.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "simpartner/text.h"

namespace simpartner::sim {
namespace {

std::string Vec(const Eigen::Vector3d& v) {
  return ShortestNumber(v.x()) + " " + ShortestNumber(v.y()) + " " + ShortestNumber(v.z());
}

std::string Quat(const Eigen::Matrix3d& rotation) {
  Eigen::Quaterniond q(rotation);
  q.normalize();
  return ShortestNumber(q.w()) + " " + ShortestNumber(q.x()) + " " + ShortestNumber(q.y()) + " " +
         ShortestNumber(q.z());
}

// MuJoCo's hinge and slide axes of one of our joints, in the child's
// frame. MuJoCo turns a body's joints in their order, the first about an
// axis fixed in the parent, the last about one fixed in the child; ODE's
// universal and hinge2 fix axis 1 in body1 and axis 2 in body2, so the
// order follows which of the two is the parent.
struct AxisOrder {
  int first, second;
};
AxisOrder OrderOfAxes(bool child_is_body1) {
  return child_is_body1 ? AxisOrder{1, 0} : AxisOrder{0, 1};
}

class EngineWriter {
 public:
  EngineWriter(const model::FlatModel& model, const model::BodyTree& tree, const Parameters& params)
      : model_(model), tree_(tree), params_(params) {}

  std::string Run() {
    std::ostringstream out;
    const model::World& world = *model_.world;
    // Sizes: room for every pair of geoms to touch at a few points.
    const size_t geoms = model_.bodies.size() + 2;
    const size_t contacts = 200 + 8 * geoms;
    out << "<mujoco model=\"simpartner\">\n"
        << "  <compiler angle=\"radian\" inertiafromgeom=\"false\" boundmass=\"0\" "
           "boundinertia=\"0\" balanceinertia=\"false\" settotalmass=\"-1\"/>\n"
        << "  <option timestep=\"" << ShortestNumber(params_.stepsize) << "\" gravity=\""
        << Vec(world.gravity) << "\" integrator=\"Euler\" cone=\"elliptic\" impratio=\""
        << ShortestNumber(ImpRatio()) << "\"/>\n"
        // A nanometre of margin: a box placed exactly on the ground touches
        // at all four corners (at a distance of 0 give or take rounding,
        // MuJoCo's box-plane test found two of them; ODE's finds four).
        << "  <default><geom margin=\"1e-9\"/></default>\n"
        << "  <size nconmax=\"" << contacts << "\" njmax=\"" << 6 * contacts + 8 * geoms
        << "\"/>\n";
    if (world.heightfield) {
      const model::Heightfield& h = *world.heightfield;
      out << "  <asset><hfield name=\"" << kMjcfField << "\" nrow=\"" << h.rows << "\" ncol=\""
          << h.columns << "\" size=\"" << ShortestNumber(h.width / 2) << " "
          << ShortestNumber(h.depth / 2) << " 1 " << ShortestNumber(h.thickness)
          << "\"/></asset>\n";
    }
    out << "  <worldbody>\n";
    WriteGround(out);
    for (int b : tree_.order) {
      if (tree_.nodes[static_cast<size_t>(b)].parent < 0) WriteBody(b, "    ", out);
    }
    for (size_t b = 0; b < model_.bodies.size(); ++b) {
      if (!Static(static_cast<int>(b))) continue;
      const Eigen::Isometry3d& pose = model_.bodies[b].pose;
      out << "    <geom name=\"" << MjcfGeomName(static_cast<int>(b)) << "\" pos=\""
          << Vec(pose.translation()) << "\" quat=\"" << Quat(pose.linear()) << "\" "
          << Shape(*model_.bodies[b].source) << "/>\n";
    }
    out << "  </worldbody>\n";
    WriteActuators(out);
    out << "</mujoco>\n";
    return out.str();
  }

 private:
  bool Static(int body) const {
    return body < 0 || model_.bodies[static_cast<size_t>(body)].source->is_static;
  }

  // Friction rows give way by impratio times less than the normal row:
  // ODE's friction rows have their own compliance (contactSlip) beside the
  // contact CFM, so the ratio is the default CFM over contactSlip.
  double ImpRatio() const {
    return std::clamp(params_.contactSoftCFM / params_.contactSlip, 1.0, 1e6);
  }

  void WriteGround(std::ostringstream& out) const {
    const model::World& world = *model_.world;
    if (world.has_plane) {
      const Eigen::Vector3d normal = world.plane.head<3>().normalized();
      const Eigen::Vector3d at = normal * (world.plane[3] / world.plane.head<3>().norm());
      out << "    <geom name=\"" << kMjcfPlane << "\" type=\"plane\" size=\"0 0 1\" pos=\""
          << Vec(at) << "\" zaxis=\"" << Vec(normal) << "\" condim=\"6\"/>\n";
    }
    if (world.heightfield) {
      // MuJoCo's field is z up, rows along its y; ours is "up" up, rows
      // along z: local (x, y, z) = ours (x, -z, y), turned to up.
      const model::Heightfield& h = *world.heightfield;
      Eigen::Matrix3d local;
      local << 1, 0, 0,
               0, 0, 1,
               0, -1, 0;
      const Eigen::Matrix3d up = world.HeightfieldPose().linear();
      out << "    <geom name=\"" << kMjcfField << "\" type=\"hfield\" hfield=\"" << kMjcfField
          << "\" pos=\"" << Vec(h.position) << "\" quat=\"" << Quat(up * local)
          << "\" condim=\"6\"/>\n";
    }
  }

  std::string Shape(const model::Body& body) const {
    const model::Geometry& g = body.geometry;
    std::ostringstream out;
    switch (g.kind) {
      case model::GeometryKind::kBox: out << "type=\"box\" size=\"" << Vec(g.size / 2) << "\""; break;
      case model::GeometryKind::kSphere:
        out << "type=\"sphere\" size=\"" << ShortestNumber(g.size.x()) << "\"";
        break;
      case model::GeometryKind::kCylinder:
      case model::GeometryKind::kCapsule:
        out << "type=\"" << (g.kind == model::GeometryKind::kCylinder ? "cylinder" : "capsule")
            << "\" size=\"" << ShortestNumber(g.size.x()) << " " << ShortestNumber(g.size.y() / 2)
            << "\"";
        break;
      case model::GeometryKind::kNone: return "";
    }
    // Six rows room for rolling resistance; the engine lowers each contact
    // to what its materials need.
    out << " condim=\"6\"";
    return out.str();
  }

  void WriteJoint(int body, const Eigen::Isometry3d& pose, const std::string& indent,
                  std::ostringstream& out) const {
    const model::TreeNode& node = tree_.nodes[static_cast<size_t>(body)];
    if (node.free) {
      out << indent << "<freejoint/>\n";
      return;
    }
    if (node.joint < 0) return;
    const model::FlatJoint& joint = model_.joints[static_cast<size_t>(node.joint)];
    const Eigen::Vector3d anchor = pose.inverse() * joint.anchor;
    const double sign = node.joint_reversed ? -1.0 : 1.0;
    auto axis = [&](int a) {
      return Eigen::Vector3d(sign * (pose.linear().transpose() * joint.axis[a]));
    };
    switch (joint.source->kind) {
      case model::JointKind::kFixed: return;
      case model::JointKind::kBall:
        out << indent << "<joint name=\"" << MjcfJointName(node.joint, 0) << "\" type=\"ball\" pos=\""
            << Vec(anchor) << "\"/>\n";
        return;
      case model::JointKind::kHinge:
      case model::JointKind::kSlider:
        out << indent << "<joint name=\"" << MjcfJointName(node.joint, 0) << "\" type=\""
            << (joint.source->kind == model::JointKind::kHinge ? "hinge" : "slide")
            << "\" pos=\"" << Vec(anchor) << "\" axis=\"" << Vec(axis(0)) << "\"/>\n";
        return;
      case model::JointKind::kUniversal:
      case model::JointKind::kHinge2: {
        const AxisOrder order = OrderOfAxes(!node.joint_reversed);
        for (int a : {order.first, order.second})
          out << indent << "<joint name=\"" << MjcfJointName(node.joint, a)
              << "\" type=\"hinge\" pos=\"" << Vec(anchor) << "\" axis=\"" << Vec(axis(a))
              << "\"/>\n";
        return;
      }
    }
  }

  void WriteBody(int body, const std::string& indent, std::ostringstream& out) const {
    const model::TreeNode& node = tree_.nodes[static_cast<size_t>(body)];
    const model::FlatBody& flat = model_.bodies[static_cast<size_t>(body)];
    const model::Body& source = *flat.source;
    const Eigen::Isometry3d relative =
        node.parent < 0 ? flat.pose
                        : model_.bodies[static_cast<size_t>(node.parent)].pose.inverse() * flat.pose;
    out << indent << "<body name=\"" << MjcfBodyName(body) << "\" pos=\""
        << Vec(relative.translation()) << "\" quat=\"" << Quat(relative.linear()) << "\">\n";
    const std::string inner = indent + "  ";
    WriteJoint(body, flat.pose, inner, out);
    const Eigen::Matrix3d& i = source.inertia;
    out << inner << "<inertial pos=\"" << Vec(source.com) << "\" mass=\""
        << ShortestNumber(source.mass) << "\" fullinertia=\"" << ShortestNumber(i(0, 0)) << " "
        << ShortestNumber(i(1, 1)) << " " << ShortestNumber(i(2, 2)) << " "
        << ShortestNumber(i(0, 1)) << " " << ShortestNumber(i(0, 2)) << " "
        << ShortestNumber(i(1, 2)) << "\"/>\n";
    const std::string shape = Shape(source);
    if (!shape.empty())
      out << inner << "<geom name=\"" << MjcfGeomName(body) << "\" " << shape << "/>\n";
    for (int child : node.children) WriteBody(child, inner, out);
    out << indent << "</body>\n";
  }

  // One servo per joint axis: any of them may get a motor (an actuator's
  // controller or a command). Gains and limits are set per step.
  void WriteActuators(std::ostringstream& out) const {
    std::ostringstream list;
    for (const model::TreeNode& node : tree_.nodes) {
      if (node.joint < 0) continue;  // a root, or welded: no joint of its own
      const model::FlatJoint& joint = model_.joints[static_cast<size_t>(node.joint)];
      for (int a = 0; a < joint.num_axes; ++a)
        list << "    <general name=\"" << MjcfActuatorName(node.joint, a) << "\" joint=\""
             << MjcfJointName(node.joint, a)
             << "\" gaintype=\"fixed\" gainprm=\"1\" biastype=\"affine\" biasprm=\"0 0 0\" "
                "ctrllimited=\"false\" forcelimited=\"true\" forcerange=\"-1 1\"/>\n";
    }
    if (!list.str().empty()) out << "  <actuator>\n" << list.str() << "  </actuator>\n";
  }

  const model::FlatModel& model_;
  const model::BodyTree& tree_;
  const Parameters& params_;
};

}  // namespace

std::string MjcfBodyName(int body) { return "b" + std::to_string(body); }
std::string MjcfGeomName(int body) { return "g" + std::to_string(body); }
std::string MjcfJointName(int joint, int axis) {
  return "j" + std::to_string(joint) + "_" + std::to_string(axis);
}
std::string MjcfActuatorName(int joint, int axis) {
  return "a" + std::to_string(joint) + "_" + std::to_string(axis);
}

std::string EngineMjcf(const model::FlatModel& model, const model::BodyTree& tree,
                       const Parameters& params) {
  return EngineWriter(model, tree, params).Run();
}

}  // namespace simpartner::sim
