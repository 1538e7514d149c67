#include "simpartner/convert/urdf_import.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "xml_text.h"
#include "simpartner/model/loader.h"
#include "xml_lines.h"

namespace simpartner::convert {
namespace {

// z-up (URDF) to y-up (ours): (x, y, z) -> (x, z, -y).
Eigen::Matrix3d ZUpToYUp() {
  Eigen::Matrix3d d;
  d << 1, 0, 0,
       0, 0, 1,
       0, -1, 0;
  return d;
}

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  t.linear() = q.normalized().toRotationMatrix();
  return t;
}

// Collects urdfdom's console_bridge messages while it parses. console_bridge
// keeps one output handler per process, so parses take turns.
class CapturedLog : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
  }
  std::vector<std::string> messages;
};

std::mutex& ConsoleBridgeMutex() {
  static std::mutex mutex;
  return mutex;
}

// A name the XML ID type accepts (ours are IDs): letter or '_' first,
// then letters, digits, '_', '-', '.'.
bool IsXmlId(const std::string& name) {
  if (name.empty()) return false;
  const auto letter = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  };
  if (!letter(name[0])) return false;
  return std::all_of(name.begin(), name.end(), [&](char c) {
    return letter(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
  });
}

struct BodyOut {
  std::string name;
  std::string type;               // Body, Box, Sphere, Cylinder
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box lx ly lz; radius, length
  double mass = 0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // robot frame, y-up
  int line = 0;
};

struct JointOut {
  std::string name;
  std::string type;               // Fixed, Hinge, Slider
  std::string body1, body2;       // child, parent
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  bool limited = false;
  double lo = 0, hi = 0;
  std::string actuator_type;      // "" = none
};

class Importer {
 public:
  Importer(const std::string& file_name, const UrdfLines& lines, const UrdfImportOptions& options)
      : file_(file_name), lines_(lines), options_(options) {}

  void Walk(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& link,
            const Eigen::Isometry3d& link_pose);
  std::string Write(const std::string& robot_name) const;
  void Fail(int line, const std::string& message) { diagnostics_.Add(file_, line, "", message); }
  int LinkLine(const std::string& name) const {
    auto it = lines_.links.find(name);
    return it == lines_.links.end() ? lines_.robot : it->second;
  }
  int JointLine(const std::string& name) const {
    auto it = lines_.joints.find(name);
    return it == lines_.joints.end() ? lines_.robot : it->second;
  }
  const DiagnosticList& diagnostics() const { return diagnostics_; }
  std::vector<std::string> notes;

 private:
  void AddBody(const urdf::Link& link, const Eigen::Isometry3d& link_pose);
  void AddJoint(const urdf::Joint& joint, const Eigen::Isometry3d& parent_pose);
  // The collision shape as (kind, size, shape frame in the link frame);
  // false after a diagnostic.
  bool Shape(const urdf::Link& link, const urdf::Collision& collision, BodyOut* body,
             Eigen::Isometry3d* shape_in_link);

  std::string file_;
  const UrdfLines& lines_;
  UrdfImportOptions options_;
  DiagnosticList diagnostics_;
  std::vector<BodyOut> bodies_;
  std::vector<JointOut> joints_;
};

bool Importer::Shape(const urdf::Link& link, const urdf::Collision& collision, BodyOut* body,
                     Eigen::Isometry3d* shape_in_link) {
  *shape_in_link = ToIsometry(collision.origin);
  const int line = lines_.collisions.count(link.name) != 0 &&
                           !lines_.collisions.at(link.name).empty()
                       ? lines_.collisions.at(link.name).front()
                       : LinkLine(link.name);
  if (!collision.geometry) {
    Fail(line, "link '" + link.name + "': collision without geometry");
    return false;
  }
  switch (collision.geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*collision.geometry);
      body->type = "Box";
      body->size = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
      return true;
    }
    case urdf::Geometry::SPHERE: {
      body->type = "Sphere";
      body->size.x() = static_cast<const urdf::Sphere&>(*collision.geometry).radius;
      return true;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*collision.geometry);
      body->type = "Cylinder";
      body->size = Eigen::Vector3d(cylinder.radius, cylinder.length, 0);
      return true;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*collision.geometry);
      if (!options_.mesh_as_box) {
        Fail(line, "link '" + link.name + "': mesh collision shape '" + mesh.filename +
                       "' is not supported (box, cylinder and sphere are; --mesh-as-box uses "
                       "the mesh's bounding box)");
        return false;
      }
      std::string path = mesh.filename;
      if (path.rfind("package://", 0) == 0) {
        Fail(line, "link '" + link.name + "': cannot use the bounding box of mesh '" + path +
                       "': package:// paths need a ROS package path (write the file's path)");
        return false;
      }
      if (path.rfind("file://", 0) == 0) path = path.substr(7);
      std::filesystem::path resolved(path);
      if (resolved.is_relative())
        resolved = std::filesystem::path(file_).parent_path() / resolved;
      MeshBounds bounds;
      try {
        bounds = ReadMeshBounds(resolved.string());
      } catch (const ConvertError& error) {
        Fail(line, "link '" + link.name + "': cannot use the bounding box of mesh '" +
                       mesh.filename + "': " + error.diagnostics().items().front().message);
        return false;
      }
      const Eigen::Vector3d scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      Eigen::Vector3d lo, hi;
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(bounds.min[k] * scale[k], bounds.max[k] * scale[k]);
        hi[k] = std::max(bounds.min[k] * scale[k], bounds.max[k] * scale[k]);
      }
      body->type = "Box";
      body->size = hi - lo;
      shape_in_link->translate((lo + hi) / 2);
      notes.push_back("link '" + link.name + "': mesh '" + mesh.filename + "' became its bounding box " +
                      NumberText(body->size.x()) + " x " + NumberText(body->size.y()) + " x " +
                      NumberText(body->size.z()) + " m");
      return true;
    }
  }
  Fail(line, "link '" + link.name + "': unknown collision geometry");
  return false;
}

void Importer::AddBody(const urdf::Link& link, const Eigen::Isometry3d& link_pose) {
  BodyOut body;
  body.name = link.name;
  body.line = LinkLine(link.name);
  if (!IsXmlId(link.name)) {
    Fail(body.line, "link name '" + link.name +
                        "' cannot be a name in our files (a letter or '_' first, then letters, "
                        "digits, '_', '-', '.')");
    return;
  }
  if (!link.inertial) {
    Fail(body.line, "link '" + link.name +
                        "' has no <inertial>: every body of ours has a mass (give it one, or "
                        "merge this frame into its parent)");
    return;
  }
  std::vector<urdf::CollisionSharedPtr> collisions = link.collision_array;
  if (collisions.empty() && link.collision) collisions.push_back(link.collision);
  if (collisions.size() > 1) {
    const auto& at = lines_.collisions.count(link.name) != 0 ? lines_.collisions.at(link.name)
                                                            : std::vector<int>{};
    Fail(at.size() > 1 ? at[1] : body.line,
         "link '" + link.name + "' has " + std::to_string(collisions.size()) +
             " collision shapes; a body of ours has one (split the link into links joined by "
             "fixed joints)");
    return;
  }
  Eigen::Isometry3d shape_in_link = Eigen::Isometry3d::Identity();
  body.type = "Body";
  if (!collisions.empty() && !Shape(link, *collisions.front(), &body, &shape_in_link)) return;

  // The body frame is the shape's frame; the centre of mass and inertia
  // are expressed in it.
  const Eigen::Isometry3d body_pose = link_pose * shape_in_link;
  const Eigen::Isometry3d inertial = ToIsometry(link.inertial->origin);
  body.mass = link.inertial->mass;
  body.com = shape_in_link.inverse() * inertial.translation();
  Eigen::Matrix3d tensor;
  tensor << link.inertial->ixx, link.inertial->ixy, link.inertial->ixz,
            link.inertial->ixy, link.inertial->iyy, link.inertial->iyz,
            link.inertial->ixz, link.inertial->iyz, link.inertial->izz;
  const Eigen::Matrix3d to_body = shape_in_link.linear().transpose() * inertial.linear();
  body.inertia = to_body * tensor * to_body.transpose();
  const Eigen::Matrix3d d = ZUpToYUp();
  body.pose.linear() = d * body_pose.linear();
  body.pose.translation() = d * body_pose.translation();
  bodies_.push_back(body);
}

void Importer::AddJoint(const urdf::Joint& joint, const Eigen::Isometry3d& parent_pose) {
  JointOut out;
  out.name = joint.name;
  const int line = JointLine(joint.name);
  if (!IsXmlId(joint.name)) {
    Fail(line, "joint name '" + joint.name + "' cannot be a name in our files (a letter or '_' "
                                             "first, then letters, digits, '_', '-', '.')");
    return;
  }
  out.body1 = joint.child_link_name;  // ours: body1 relative to body2
  out.body2 = joint.parent_link_name;
  const Eigen::Isometry3d frame = parent_pose * ToIsometry(joint.parent_to_joint_origin_transform);
  const Eigen::Matrix3d d = ZUpToYUp();
  out.anchor = d * frame.translation();
  Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
  if (joint.type != urdf::Joint::FIXED && !(axis.norm() > 1e-9)) {
    Fail(line, "joint '" + joint.name + "': axis has zero length");
    return;
  }
  if (joint.type != urdf::Joint::FIXED) out.axis = (d * frame.linear() * axis).normalized();
  switch (joint.type) {
    case urdf::Joint::FIXED: out.type = "Fixed"; break;
    case urdf::Joint::CONTINUOUS:
      out.type = "Hinge";
      out.actuator_type = "JointController";
      break;
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::PRISMATIC:
      out.type = joint.type == urdf::Joint::REVOLUTE ? "Hinge" : "Slider";
      out.actuator_type = joint.type == urdf::Joint::REVOLUTE ? "AngleController" : "LinearMotor";
      if (joint.limits && joint.limits->lower < joint.limits->upper) {
        out.limited = true;
        out.lo = joint.limits->lower;
        out.hi = joint.limits->upper;
      }
      break;
    case urdf::Joint::FLOATING:
      Fail(line, "joint '" + joint.name +
                     "': floating joints are not supported (our robot is one connected body "
                     "graph; place separate robots in a world instead)");
      return;
    case urdf::Joint::PLANAR:
      Fail(line, "joint '" + joint.name + "': planar joints are not supported (ours: fixed, "
                                          "revolute, continuous, prismatic)");
      return;
    default:
      Fail(line, "joint '" + joint.name + "': unknown joint type");
      return;
  }
  joints_.push_back(out);
}

void Importer::Walk(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& link,
                    const Eigen::Isometry3d& link_pose) {
  AddBody(*link, link_pose);
  for (const urdf::JointSharedPtr& joint : link->child_joints) {
    AddJoint(*joint, link_pose);
    urdf::LinkConstSharedPtr child = model.getLink(joint->child_link_name);
    if (child)
      Walk(model, child,
           link_pose * ToIsometry(joint->parent_to_joint_origin_transform));
  }
}

std::string Vector(const char* tag, const Eigen::Vector3d& v) {
  return std::string("<") + tag + "><x>" + NumberText(v.x()) + "</x><y>" + NumberText(v.y()) +
         "</y><z>" + NumberText(v.z()) + "</z></" + tag + ">";
}

std::string Transformation(const Eigen::Isometry3d& pose, const std::string& indent) {
  std::ostringstream out;
  out << indent << "<transformation>\n";
  for (int r = 0; r < 3; ++r) {
    out << indent << "  ";
    for (int c = 0; c < 4; ++c) {
      const double value = c < 3 ? pose.linear()(r, c) : pose.translation()[r];
      // Rotations come out of quaternions: values within 1e-15 of 0 are 0.
      const double clean = std::abs(value) < 1e-15 ? 0.0 : value;
      out << "<T" << r << c << ">" << NumberText(clean) << "</T" << r << c << ">";
    }
    out << "\n";
  }
  out << indent << "</transformation>\n";
  return out.str();
}

std::string Importer::Write(const std::string& robot_name) const {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<!-- Converted from URDF " << EscapeXml(file_) << " by simpartner-convert.\n"
      << "     Frames: URDF z-up (x forward, y left, z up) became y-up (x forward, y up,\n"
      << "     z right): (x, y, z) -> (x, z, -y). Each body's frame is its URDF\n"
      << "     collision frame; the centre of mass and inertia are in it. Every\n"
      << "     movable joint got an actuator (continuous: JointController, revolute:\n"
      << "     AngleController, prismatic: LinearMotor) named <joint>Motor. -->\n"
      << "<robot name=\"" << EscapeXml(robot_name) << "\" version=\"1\">\n";
  for (const BodyOut& body : bodies_) {
    out << "  <body type=\"" << body.type << "\" name=\"" << body.name << "\">\n"
        << "    <mass>" << NumberText(body.mass) << "</mass>\n";
    if (body.type == "Box") out << "    " << Vector("size", body.size) << "\n";
    if (body.type == "Sphere" || body.type == "Cylinder")
      out << "    <radius>" << NumberText(body.size.x()) << "</radius>\n";
    if (body.type == "Cylinder") out << "    <length>" << NumberText(body.size.y()) << "</length>\n";
    out << "    " << Vector("centerOfMass", body.com) << "\n";
    const Eigen::Matrix3d& i = body.inertia;
    out << "    <inertia><Ixx>" << NumberText(i(0, 0)) << "</Ixx><Iyy>" << NumberText(i(1, 1))
        << "</Iyy><Izz>" << NumberText(i(2, 2)) << "</Izz><Ixy>" << NumberText(i(0, 1))
        << "</Ixy><Ixz>" << NumberText(i(0, 2)) << "</Ixz><Iyz>" << NumberText(i(1, 2))
        << "</Iyz></inertia>\n";
    out << Transformation(body.pose, "    ") << "  </body>\n";
  }
  for (const JointOut& joint : joints_) {
    out << "  <joint type=\"" << joint.type << "\" name=\"" << joint.name << "\">\n"
        << "    <body1>" << joint.body1 << "</body1><body2>" << joint.body2 << "</body2>\n";
    if (joint.type != "Fixed") {
      out << "    " << Vector("anchor", joint.anchor) << "\n"
          << "    " << Vector("axis1", joint.axis) << "\n";
    }
    if (joint.limited)
      out << "    <limits><lo>" << NumberText(joint.lo) << "</lo><hi>" << NumberText(joint.hi)
          << "</hi></limits>\n";
    out << "  </joint>\n";
  }
  for (const JointOut& joint : joints_) {
    if (joint.actuator_type.empty()) continue;
    out << "  <actuator type=\"" << joint.actuator_type << "\" name=\"" << joint.name
        << "Motor\"><jointRef>" << joint.name << "</jointRef></actuator>\n";
  }
  out << "</robot>\n";
  return out.str();
}

// The line of the element an urdfdom message names: its names come in
// square brackets ("child link [b] of joint [j] not found"); a joint
// named is the more precise place, then a link.
int LineOfMessage(const std::string& message, const UrdfLines& lines) {
  int link_line = 0;
  for (size_t open = message.find('['); open != std::string::npos;
       open = message.find('[', open + 1)) {
    const size_t close = message.find(']', open);
    if (close == std::string::npos) break;
    const std::string name = message.substr(open + 1, close - open - 1);
    const bool says_joint = open >= 6 && (message.compare(open - 6, 5, "joint") == 0 ||
                                          message.compare(open - 6, 5, "Joint") == 0);
    if (lines.joints.count(name) != 0 && (says_joint || lines.links.count(name) == 0))
      return lines.joints.at(name);
    if (link_line == 0 && lines.links.count(name) != 0) link_line = lines.links.at(name);
  }
  return link_line != 0 ? link_line : lines.robot;
}

}  // namespace

UrdfImportResult ImportUrdf(const std::string& urdf_text, const std::string& file_name,
                            const UrdfImportOptions& options) {
  const UrdfLines lines = ReadXmlLines(urdf_text, file_name);
  if (lines.root_name != "robot" || lines.has_bodies) {
    DiagnosticList diagnostics;
    diagnostics.Add(file_name, lines.robot, "",
                    "not a URDF file: the root element is <" + lines.root_name +
                        "> with " + (lines.has_bodies ? "<body>" : "no <link>") +
                        " elements (URDF: <robot> with <link> and <joint>)");
    throw ConvertError(diagnostics);
  }

  urdf::ModelInterfaceSharedPtr model;
  CapturedLog log;
  {
    std::lock_guard<std::mutex> lock(ConsoleBridgeMutex());
    console_bridge::useOutputHandler(&log);
    try {
      model = urdf::parseURDF(urdf_text);
    } catch (const std::exception& error) {
      log.messages.push_back(error.what());
    }
    console_bridge::restorePreviousOutputHandler();
  }
  if (!model) {
    DiagnosticList diagnostics;
    if (log.messages.empty()) log.messages.push_back("urdfdom refused the file");
    // urdfdom's last message is the general one ("Model Parsing the xml
    // failed"); the first names the element.
    const std::string& message = log.messages.front();
    diagnostics.Add(file_name, LineOfMessage(message, lines), "", message);
    throw ConvertError(diagnostics);
  }

  Importer importer(file_name, lines, options);
  // Names are unique across bodies, joints and actuators in our files.
  std::map<std::string, int> names;
  auto claim = [&](const std::string& name, int line, const std::string& what) {
    auto [it, fresh] = names.emplace(name, line);
    if (!fresh)
      importer.Fail(line, what + " '" + name + "' has the name of another element (line " +
                              std::to_string(it->second) +
                              "); names are unique across bodies, joints and actuators in our "
                              "robot files");
  };
  for (const auto& [name, line] : lines.links) claim(name, line, "link");
  for (const auto& [name, line] : lines.joints) claim(name, line, "joint");
  for (const auto& [name, joint] : model->joints_) {
    if (joint->type != urdf::Joint::FIXED)
      claim(name + "Motor", importer.JointLine(name), "actuator of joint");
  }
  importer.Walk(*model, model->getRoot(), Eigen::Isometry3d::Identity());
  if (!importer.diagnostics().empty()) throw ConvertError(importer.diagnostics());

  UrdfImportResult result;
  result.robot_xml = importer.Write(model->getName());
  result.notes = importer.notes;
  // Our loader has the last word (ranges, inertia checks); what it refuses
  // is reported at the URDF link it came from.
  model::RobotLoadResult check = model::ParseRobot(result.robot_xml, file_name + " (converted)");
  if (!check.robot) {
    DiagnosticList diagnostics;
    for (const Diagnostic& found : check.diagnostics.items()) {
      int line = lines.robot;
      for (const auto& [name, at] : lines.links)
        if (found.message.find("'" + name + "'") != std::string::npos) line = at;
      for (const auto& [name, at] : lines.joints)
        if (found.message.find("'" + name + "'") != std::string::npos) line = at;
      diagnostics.Add(file_name, line, "",
                      "the converted robot is refused by our loader: " +
                          (found.element.empty() ? "" : found.element + ": ") + found.message);
    }
    throw ConvertError(diagnostics);
  }
  return result;
}

MeshBounds ReadMeshBounds(const std::string& path) {
  auto fail = [&](const std::string& why) {
    DiagnosticList diagnostics;
    diagnostics.Add(path, 0, "", why);
    return ConvertError(diagnostics);
  };
  std::string contents;
  try {
    if (!model::ReadFileFromDisk(path, &contents)) throw fail("cannot read the file");
  } catch (const model::ModelFileError& error) {
    throw fail(error.what());
  }
  MeshBounds bounds;
  for (int k = 0; k < 3; ++k) {
    bounds.min[k] = INFINITY;
    bounds.max[k] = -INFINITY;
  }
  size_t points = 0;
  auto add = [&](const double p[3]) {
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k])) throw fail("a vertex coordinate is not finite");
      bounds.min[k] = std::min(bounds.min[k], p[k]);
      bounds.max[k] = std::max(bounds.max[k], p[k]);
    }
    ++points;
  };
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".stl") {
    // Binary STL: 80-byte header, triangle count, 50 bytes per triangle.
    uint32_t count = 0;
    if (contents.size() >= 84) std::memcpy(&count, contents.data() + 80, 4);
    if (contents.size() >= 84 && contents.size() == 84 + 50ull * count) {
      for (uint32_t t = 0; t < count; ++t) {
        for (int v = 0; v < 3; ++v) {
          float xyz[3];
          std::memcpy(xyz, contents.data() + 84 + 50ull * t + 12 + 12 * v, sizeof xyz);
          const double p[3] = {xyz[0], xyz[1], xyz[2]};
          add(p);
        }
      }
    } else {
      std::istringstream in(contents);
      std::string word;
      while (in >> word) {
        if (word != "vertex") continue;
        double p[3];
        if (!(in >> p[0] >> p[1] >> p[2])) throw fail("an ASCII STL vertex without 3 numbers");
        add(p);
      }
    }
  } else if (extension == ".obj") {
    std::istringstream in(contents);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("v ", 0) != 0) continue;
      std::istringstream values(line.substr(2));
      double p[3];
      if (!(values >> p[0] >> p[1] >> p[2])) throw fail("an OBJ vertex without 3 numbers");
      add(p);
    }
  } else {
    throw fail("only STL and OBJ meshes are read (not '" + extension + "')");
  }
  if (points == 0) throw fail("the mesh has no vertices");
  return bounds;
}

}  // namespace simpartner::convert
