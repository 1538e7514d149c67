#include "simpartner/model/loader.h"

#include <Eigen/Eigenvalues>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "simpartner/data_paths.h"
#include "simpartner/text.h"
#include "simpartner/xml_document.h"
#include "dtd_texts.h"  // generated: kWorldDtdText, kRobotDtdText

namespace simpartner::model {
namespace {

// Files written with three decimals (0.707 for cos 45 deg) must load: their
// |R^T R - I| is 3e-4. Two decimals (0.71: 8e-3) or any real shear fail.
constexpr double kOrthonormalTolerance = 2e-3;
constexpr const char* kWorldBodyName = "world";

// Walks a validated document and reports semantic problems with lines.
class Reader {
 public:
  Reader(std::string file_name, DiagnosticList* diagnostics)
      : file_(std::move(file_name)), diagnostics_(diagnostics) {}

  const std::string& file() const { return file_; }
  SourceLocation Where(const xmlNode* node) const {
    return SourceLocation{file_, xml::Line(node)};
  }
  void Error(const xmlNode* node, const std::string& message) {
    xml::AddAt(diagnostics_, file_, node, message);
  }
  void ErrorAt(const SourceLocation& where, const std::string& element,
               const std::string& message) {
    diagnostics_->Add(where.file, where.line, element, message);
  }
  size_t ErrorCount() const { return diagnostics_->size(); }

  // A finite number from the element's text; reports and returns nullopt
  // otherwise. what names the quantity for the message.
  std::optional<double> Number(const xmlNode* node, const std::string& what) {
    if (node == nullptr) return std::nullopt;
    const std::string text = xml::Text(node);
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end == text.c_str() || *end != '\0') {
      Error(node, what + ": '" + text + "' is not a number");
      return std::nullopt;
    }
    if (!std::isfinite(value)) {
      Error(node, what + ": '" + text + "' is not a finite number");
      return std::nullopt;
    }
    return value;
  }

  // Number of child `name`, or fallback when the child is absent.
  double NumberOr(const xmlNode* parent, const char* name, double fallback,
                  const std::string& what, bool* ok) {
    const xmlNode* child = xml::Child(parent, name);
    if (child == nullptr) return fallback;
    const auto value = Number(child, what + " " + name);
    if (!value) {
      *ok = false;
      return fallback;
    }
    return *value;
  }

  std::optional<Eigen::Vector3d> Vector(const xmlNode* node, const char* cx, const char* cy,
                                        const char* cz, const std::string& what) {
    if (node == nullptr) return std::nullopt;
    const auto x = Number(xml::Child(node, cx), what + " " + cx);
    const auto y = Number(xml::Child(node, cy), what + " " + cy);
    const auto z = Number(xml::Child(node, cz), what + " " + cz);
    if (!x || !y || !z) return std::nullopt;
    return Eigen::Vector3d(*x, *y, *z);
  }
  std::optional<Eigen::Vector3d> Vector(const xmlNode* node, const std::string& what) {
    return Vector(node, "x", "y", "z", what);
  }

  // The original's 3x4 transformation; the rotation part must be a proper
  // rotation (orthonormal, det +1) within kOrthonormalTolerance, and is
  // re-orthonormalised so that rounded values in files do not shear bodies.
  std::optional<Eigen::Isometry3d> Transformation(const xmlNode* node, const std::string& what) {
    if (node == nullptr) return std::nullopt;
    Eigen::Matrix<double, 3, 4> t;
    bool ok = true;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        const std::string tag = "T" + std::to_string(r) + std::to_string(c);
        const auto value = Number(xml::Child(node, tag.c_str()), what + " " + tag);
        if (!value) {
          ok = false;
          continue;
        }
        t(r, c) = *value;
      }
    }
    if (!ok) return std::nullopt;
    const Eigen::Matrix3d rotation = t.leftCols<3>();
    const double error = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity())
                             .cwiseAbs().maxCoeff();
    if (error > kOrthonormalTolerance || rotation.determinant() < 0) {
      std::ostringstream message;
      message << what << ": rotation part T00..T22 is not a rotation matrix "
              << "(|R^T R - I| = " << FormatNumber(error, 10) << ", det = "
              << FormatNumber(rotation.determinant(), 10) << ")";
      Error(node, message.str());
      return std::nullopt;
    }
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(rotation).normalized().toRotationMatrix();
    pose.translation() = t.col(3);
    return pose;
  }

 private:
  std::string file_;
  DiagnosticList* diagnostics_;
};

std::optional<Material> ReadMaterial(Reader& reader, const xmlNode* node) {
  Material m;
  m.name = xml::Attribute(node, "name").value_or("");
  m.where = reader.Where(node);
  const std::string what = "material '" + m.name + "'";
  bool ok = true;
  auto optional_number = [&](const char* field) -> std::optional<double> {
    const xmlNode* child = xml::Child(node, field);
    if (child == nullptr) return std::nullopt;
    const auto value = reader.Number(child, what + " " + field);
    if (!value) ok = false;
    return value;
  };
  m.mu = reader.NumberOr(node, "mu", m.mu, what, &ok);
  m.mu2 = optional_number("mu2");
  if (const xmlNode* d = xml::Child(node, "frictionDirection")) {
    const std::string text = xml::Text(d);
    if (text == ToString(FrictionDirection::kSlip)) {
      m.friction_direction = FrictionDirection::kSlip;
    } else if (text == ToString(FrictionDirection::kRolling)) {
      m.friction_direction = FrictionDirection::kRolling;
    } else {
      reader.Error(d, what + ": frictionDirection '" + text + "' is not one of slip, rolling");
      ok = false;
    }
  }
  m.bounce = reader.NumberOr(node, "bounce", m.bounce, what, &ok);
  m.bounce_velocity = reader.NumberOr(node, "bounceVelocity", m.bounce_velocity, what, &ok);
  m.soft_erp = reader.NumberOr(node, "softERP", m.soft_erp, what, &ok);
  m.soft_cfm = reader.NumberOr(node, "softCFM", m.soft_cfm, what, &ok);
  m.stiffness = optional_number("stiffness");
  m.damping = optional_number("damping");
  m.rolling_friction = reader.NumberOr(node, "rollingFriction", m.rolling_friction, what, &ok);
  auto at = [&](const char* field) {
    return xml::Child(node, field) ? xml::Child(node, field) : node;
  };
  auto range = [&](double value, double lo, double hi, const char* field) {
    if (value < lo || value > hi) {
      reader.Error(at(field), what + ": " + field + " " + FormatNumber(value, 10) +
                                  " is out of range [" + FormatNumber(lo, 10) + ", " +
                                  FormatNumber(hi, 10) + "]");
      ok = false;
    }
  };
  range(m.mu, 0.0, 1e6, "mu");
  if (m.mu2) range(*m.mu2, 0.0, 1e6, "mu2");
  range(m.bounce, 0.0, 1.0, "bounce");
  range(m.bounce_velocity, 0.0, 1e6, "bounceVelocity");
  range(m.soft_erp, 0.0, 1.0, "softERP");
  range(m.soft_cfm, 0.0, 1.0, "softCFM");
  range(m.rolling_friction, 0.0, 1.0, "rollingFriction");
  // A zero stiffness would make ERP 0: nothing holds the bodies apart.
  if (m.stiffness && (*m.stiffness <= 0.0 || *m.stiffness > limits::kMaxContactStiffness)) {
    reader.Error(at("stiffness"), what + ": stiffness " + FormatNumber(*m.stiffness, 10) +
                                      " N/m is out of range (0, " +
                                      FormatNumber(limits::kMaxContactStiffness, 10) + "]");
    ok = false;
  }
  if (m.damping) range(*m.damping, 0.0, limits::kMaxContactDamping, "damping");
  // One softness, given one way: per step or physical.
  const bool per_step = xml::Child(node, "softERP") || xml::Child(node, "softCFM");
  const bool physical = m.stiffness || m.damping;
  if (per_step && physical) {
    reader.Error(at(m.stiffness ? "stiffness" : "damping"),
                 what + ": stiffness/damping and softERP/softCFM both give the contact's "
                        "softness; give one of the two");
    ok = false;
  } else if (m.stiffness.has_value() != m.damping.has_value()) {
    reader.Error(at(m.stiffness ? "stiffness" : "damping"),
                 what + ": " + (m.stiffness ? "stiffness without damping" : "damping without stiffness") +
                     "; give both (damping 0 for an undamped contact)");
    ok = false;
  }
  if (!ok) return std::nullopt;
  return m;
}

GeometryKind ParseGeometryKind(const std::string& type) {
  if (type == "Box") return GeometryKind::kBox;
  if (type == "Sphere") return GeometryKind::kSphere;
  if (type == "Cylinder") return GeometryKind::kCylinder;
  if (type == "Capsule") return GeometryKind::kCapsule;
  return GeometryKind::kNone;
}

std::string Range(double lo, double hi, const char* unit) {
  return "[" + FormatNumber(lo, 10) + ", " + FormatNumber(hi, 10) + "]" + unit;
}

std::string VectorText(const Eigen::Vector3d& v) {
  return "(" + FormatNumber(v.x(), 10) + ", " + FormatNumber(v.y(), 10) + ", " + FormatNumber(v.z(), 10) + ")";
}

// True when every coordinate of p is within limits::kMaxCoordinate.
bool CoordinatesInRange(const Eigen::Vector3d& p) {
  return p.cwiseAbs().maxCoeff() <= limits::kMaxCoordinate;
}

std::string CoordinateRangeText() {
  return "|x|, |y|, |z| <= " + FormatNumber(limits::kMaxCoordinate, 10) + " m";
}

// The physical ranges of one body (models/README.md, "Physical ranges"):
// each problem at the line of the element that sets the value.
void CheckBodyRanges(Reader& reader, const xmlNode* node, const Body& body,
                     const std::string& what) {
  using namespace limits;
  const size_t errors_before = reader.ErrorCount();
  auto child_or_node = [&](const char* name) {
    const xmlNode* child = xml::Child(node, name);
    return child != nullptr ? child : node;
  };
  if (!body.is_static && (body.mass < kMinMass || body.mass > kMaxMass)) {
    reader.Error(child_or_node("mass"), what + ": mass " + FormatNumber(body.mass, 10) +
                                            " kg is out of range " +
                                            Range(kMinMass, kMaxMass, " kg"));
  }
  const Geometry& g = body.geometry;
  auto size = [&](double value, const char* element, const std::string& field) {
    if (value < kMinSize || value > kMaxSize)
      reader.Error(child_or_node(element), what + ": " + field + " " + FormatNumber(value, 10) +
                                               " m is out of range " +
                                               Range(kMinSize, kMaxSize, " m"));
  };
  switch (g.kind) {
    case GeometryKind::kNone: break;
    case GeometryKind::kBox:
      for (int i = 0; i < 3; ++i) size(g.size[i], "size", std::string("size ") + "xyz"[i]);
      break;
    case GeometryKind::kSphere: size(g.size.x(), "radius", "radius"); break;
    case GeometryKind::kCylinder:
    case GeometryKind::kCapsule:
      size(g.size.x(), "radius", "radius");
      size(g.size.y(), "length", "length");
      break;
  }
  if (!CoordinatesInRange(body.pose.translation()))
    reader.Error(child_or_node("transformation"),
                 what + ": position " + VectorText(body.pose.translation()) +
                     " m is out of range: " + CoordinateRangeText());
  if (!CoordinatesInRange(body.com))
    reader.Error(child_or_node("centerOfMass"), what + ": centerOfMass " +
                                                    VectorText(body.com) +
                                                    " m is out of range: " + CoordinateRangeText());
  if (body.linear_velocity.norm() > kMaxLinearSpeed)
    reader.Error(child_or_node("translationalVelocity"),
                 what + ": translationalVelocity " + VectorText(body.linear_velocity) +
                     " m/s is out of range: speed at most " + FormatNumber(kMaxLinearSpeed, 10) +
                     " m/s");
  if (body.angular_velocity.norm() > kMaxAngularSpeed)
    reader.Error(child_or_node("rotationalVelocity"),
                 what + ": rotationalVelocity " + VectorText(body.angular_velocity) +
                     " rad/s is out of range: rotation at most " +
                     FormatNumber(kMaxAngularSpeed, 10) + " rad/s");
  if (body.is_static || reader.ErrorCount() != errors_before) return;
  // Inertia: of the file, or of the solid when computed (then a problem
  // comes from the mass and size, so it is reported at the body).
  const xmlNode* at = body.inertia_given ? child_or_node("inertia") : node;
  const std::string source = body.inertia_given ? "" : " (of a uniform " +
                                                          std::string(ToString(g.kind)) +
                                                          " of this mass and size)";
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(body.inertia);
  const Eigen::Vector3d moments = solver.eigenvalues();
  const double smallest = moments.minCoeff(), largest = moments.maxCoeff();
  if (smallest < kMinMoment || largest > kMaxMoment) {
    reader.Error(at, what + ": principal moments of inertia " + VectorText(moments) +
                         " kg m^2" + source + " are out of range " +
                         Range(kMinMoment, kMaxMoment, " kg m^2"));
  } else if (largest > kMaxInertiaRatio * smallest) {
    reader.Error(at, what + ": principal moments of inertia " + VectorText(moments) +
                         " kg m^2" + source + " differ by a factor of " +
                         FormatNumber(largest / smallest, 10) + "; at most " +
                         FormatNumber(kMaxInertiaRatio, 10));
  }
}

// Reads <body> (robot) or <object> (world). Returns nullopt after
// reporting when anything is wrong.
std::optional<Body> ReadBody(Reader& reader, const xmlNode* node, const char* kind_word) {
  Body body;
  body.name = xml::Attribute(node, "name").value_or("");
  body.where = reader.Where(node);
  body.material = xml::Attribute(node, "material").value_or("");
  body.is_static = xml::Attribute(node, "static").value_or("false") == "true";
  body.geometry.kind = ParseGeometryKind(xml::Attribute(node, "type").value_or("Body"));
  const std::string what = std::string(kind_word) + " '" + body.name + "'";
  const size_t errors_before = reader.ErrorCount();

  if (body.name == kWorldBodyName)
    reader.Error(node, what + ": the name 'world' is reserved for the static world");

  const xmlNode* mass = xml::Child(node, "mass");
  if (mass != nullptr) {
    if (const auto m = reader.Number(mass, what + " mass")) {
      if (*m <= 0.0)
        reader.Error(mass, what + ": mass must be positive, got " + FormatNumber(*m, 10));
      body.mass = *m;
    }
  } else if (!body.is_static) {
    reader.Error(node, what + ": a moving body needs <mass>");
  }

  // Geometry dimensions by kind.
  const xmlNode* size = xml::Child(node, "size");
  const xmlNode* radius = xml::Child(node, "radius");
  const xmlNode* length = xml::Child(node, "length");
  auto positive = [&](const xmlNode* n, const std::string& field) -> double {
    const auto v = reader.Number(n, what + " " + field);
    if (!v) return 0.0;
    if (*v <= 0.0)
      reader.Error(n, what + ": " + field + " must be positive, got " + FormatNumber(*v, 10));
    return *v;
  };
  auto forbid = [&](const xmlNode* n, const char* field) {
    if (n != nullptr)
      reader.Error(n, what + ": a " + ToString(body.geometry.kind) + " has no <" + field + ">");
  };
  switch (body.geometry.kind) {
    case GeometryKind::kNone:
      forbid(size, "size");
      forbid(radius, "radius");
      forbid(length, "length");
      if (body.is_static) reader.Error(node, what + ": a static object needs a shape");
      break;
    case GeometryKind::kBox:
      if (size == nullptr) {
        reader.Error(node, what + ": a Box needs <size>");
      } else if (const auto s = reader.Vector(size, what + " size")) {
        for (int i = 0; i < 3; ++i) {
          if ((*s)[i] <= 0.0)
            reader.Error(size, what + ": size " + "xyz"[i] + " must be positive, got " +
                                   FormatNumber((*s)[i], 10));
        }
        body.geometry.size = *s;
      }
      forbid(radius, "radius");
      forbid(length, "length");
      break;
    case GeometryKind::kSphere:
      if (radius == nullptr) reader.Error(node, what + ": a Sphere needs <radius>");
      else body.geometry.size.x() = positive(radius, "radius");
      forbid(size, "size");
      forbid(length, "length");
      break;
    case GeometryKind::kCylinder:
    case GeometryKind::kCapsule:
      if (radius == nullptr || length == nullptr) {
        reader.Error(node, what + ": a " + ToString(body.geometry.kind) +
                               " needs <radius> and <length>");
      } else {
        body.geometry.size.x() = positive(radius, "radius");
        body.geometry.size.y() = positive(length, "length");
      }
      forbid(size, "size");
      break;
  }

  if (const xmlNode* com = xml::Child(node, "centerOfMass")) {
    if (const auto c = reader.Vector(com, what + " centerOfMass")) body.com = *c;
  }
  if (const xmlNode* inertia = xml::Child(node, "inertia")) {
    bool ok = true;
    const double ixx = reader.NumberOr(inertia, "Ixx", 0.0, what + " inertia", &ok);
    const double iyy = reader.NumberOr(inertia, "Iyy", 0.0, what + " inertia", &ok);
    const double izz = reader.NumberOr(inertia, "Izz", 0.0, what + " inertia", &ok);
    const double ixy = reader.NumberOr(inertia, "Ixy", 0.0, what + " inertia", &ok);
    const double ixz = reader.NumberOr(inertia, "Ixz", 0.0, what + " inertia", &ok);
    const double iyz = reader.NumberOr(inertia, "Iyz", 0.0, what + " inertia", &ok);
    if (ok) {
      body.inertia << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
      body.inertia_given = true;
      // A physical inertia tensor is positive definite and its principal
      // moments obey the triangle inequality.
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(body.inertia);
      const Eigen::Vector3d p = solver.eigenvalues();
      const double tolerance = 1e-9 * p.cwiseAbs().maxCoeff();
      if (p.minCoeff() <= 0.0) {
        reader.Error(inertia, what + ": inertia is not positive definite (principal moments " +
                                  FormatNumber(p[0], 10) + ", " + FormatNumber(p[1], 10) + ", " +
                                  FormatNumber(p[2], 10) + ")");
      } else if (p[0] + p[1] < p[2] - tolerance) {
        reader.Error(inertia, what + ": principal moments " + FormatNumber(p[0], 10) + ", " +
                                  FormatNumber(p[1], 10) + ", " + FormatNumber(p[2], 10) +
                                  " break the triangle inequality (no real body has them)");
      }
    }
  }
  if (const auto pose = reader.Transformation(xml::Child(node, "transformation"),
                                              what + " transformation")) {
    body.pose = *pose;
  }
  if (const xmlNode* v = xml::Child(node, "translationalVelocity")) {
    if (const auto value = reader.Vector(v, "vx", "vy", "vz", what + " translationalVelocity"))
      body.linear_velocity = *value;
  }
  if (const xmlNode* w = xml::Child(node, "rotationalVelocity")) {
    if (const auto value =
            reader.Vector(w, "omegax", "omegay", "omegaz", what + " rotationalVelocity"))
      body.angular_velocity = *value;
  }
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  if (!body.inertia_given) body.inertia = SolidInertia(body.geometry, body.mass);
  CheckBodyRanges(reader, node, body, what);
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return body;
}

JointKind ParseJointKind(const std::string& type) {
  if (type == "Hinge") return JointKind::kHinge;
  if (type == "Slider") return JointKind::kSlider;
  if (type == "Ball") return JointKind::kBall;
  if (type == "Universal") return JointKind::kUniversal;
  if (type == "Hinge2") return JointKind::kHinge2;
  return JointKind::kFixed;
}

// Reads a joint; body_exists says whether a name is a body it may join
// (the world file allows "world").
std::optional<Joint> ReadJoint(Reader& reader, const xmlNode* node,
                               const std::function<bool(const std::string&)>& body_exists,
                               const std::string& owner) {
  Joint joint;
  joint.name = xml::Attribute(node, "name").value_or("");
  joint.kind = ParseJointKind(xml::Attribute(node, "type").value_or("Fixed"));
  joint.where = reader.Where(node);
  const std::string what = "joint '" + joint.name + "'";
  const size_t errors_before = reader.ErrorCount();

  const xmlNode* b1 = xml::Child(node, "body1");
  const xmlNode* b2 = xml::Child(node, "body2");
  joint.body1 = xml::Text(b1);
  joint.body2 = xml::Text(b2);
  if (!body_exists(joint.body1))
    reader.Error(b1, what + ": body1 '" + joint.body1 + "' is not a body of " + owner);
  if (!body_exists(joint.body2))
    reader.Error(b2, what + ": body2 '" + joint.body2 + "' is not a body of " + owner);
  if (joint.body1 == joint.body2)
    reader.Error(b2, what + ": joins body '" + joint.body1 +
                         "' to itself (a joint joins exactly two bodies)");

  const int axes = AxisCount(joint.kind);
  const xmlNode* anchor = xml::Child(node, "anchor");
  const bool needs_anchor = joint.kind != JointKind::kFixed && joint.kind != JointKind::kSlider;
  if (anchor != nullptr) {
    if (const auto a = reader.Vector(anchor, what + " anchor")) {
      joint.anchor = *a;
      if (!CoordinatesInRange(*a))
        reader.Error(anchor, what + ": anchor " + VectorText(*a) + " m is out of range: " +
                                 CoordinateRangeText());
    }
  } else if (needs_anchor) {
    reader.Error(node, what + ": a " + ToString(joint.kind) + " joint needs <anchor>");
  }
  const char* axis_tags[2] = {"axis1", "axis2"};
  for (int i = 0; i < 2; ++i) {
    const xmlNode* axis = xml::Child(node, axis_tags[i]);
    if (i < axes) {
      if (axis == nullptr) {
        reader.Error(node, what + ": a " + ToString(joint.kind) + " joint needs <" +
                               axis_tags[i] + ">");
        continue;
      }
      if (const auto a = reader.Vector(axis, what + " " + axis_tags[i])) {
        if (a->norm() < 1e-9) {
          reader.Error(axis, what + ": " + axis_tags[i] + " has zero length");
        } else {
          joint.axis[i] = a->normalized();
        }
      }
    } else if (axis != nullptr) {
      reader.Error(axis, what + ": a " + ToString(joint.kind) + " joint has no <" +
                             axis_tags[i] + ">");
    }
  }
  if (axes == 2 && reader.ErrorCount() == errors_before &&
      std::abs(joint.axis[0].dot(joint.axis[1])) > 1.0 - 1e-6) {
    reader.Error(xml::Child(node, "axis2"), what + ": axis1 and axis2 are parallel");
  }
  for (const xmlNode* limits : xml::Children(node, "limits")) {
    const int axis = std::atoi(xml::Attribute(limits, "axis").value_or("1").c_str());
    if (axis < 1 || axis > axes) {
      reader.Error(limits, what + ": a " + ToString(joint.kind) + " joint has no axis " +
                               std::to_string(axis) + " to limit");
      continue;
    }
    const auto lo = reader.Number(xml::Child(limits, "lo"), what + " limits lo");
    const auto hi = reader.Number(xml::Child(limits, "hi"), what + " limits hi");
    if (!lo || !hi) continue;
    if (*lo > *hi) {
      reader.Error(limits, what + ": limits lo " + FormatNumber(*lo, 10) + " > hi " +
                               FormatNumber(*hi, 10));
      continue;
    }
    // ODE's angular stops only work within [-pi, pi].
    const bool angular = joint.kind != JointKind::kSlider;
    if (angular && (*lo < -M_PI || *hi > M_PI)) {
      reader.Error(limits, what + ": angular limits [" + FormatNumber(*lo, 10) + ", " +
                               FormatNumber(*hi, 10) + "] must lie within [-pi, pi]");
      continue;
    }
    joint.lo_stop[axis - 1] = *lo;
    joint.hi_stop[axis - 1] = *hi;
  }
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return joint;
}

// Mass ratios ODE's solver can take (models/README.md): across each joint
// between two moving bodies, and, when robot_wide, between the heaviest and
// the lightest moving body.
void CheckMassRatios(Reader& reader, const std::vector<Body>& bodies,
                     const std::vector<Joint>& joints, bool robot_wide) {
  using namespace limits;
  auto find = [&](const std::string& name) -> const Body* {
    for (const Body& b : bodies)
      if (b.name == name) return &b;
    return nullptr;
  };
  for (const Joint& joint : joints) {
    const Body* b1 = find(joint.body1);
    const Body* b2 = find(joint.body2);
    if (b1 == nullptr || b2 == nullptr || b1->is_static || b2->is_static) continue;
    const Body* heavy = b1->mass >= b2->mass ? b1 : b2;
    const Body* light = heavy == b1 ? b2 : b1;
    if (heavy->mass > kMaxJointMassRatio * light->mass)
      reader.ErrorAt(joint.where, "joint",
                     "joint '" + joint.name + "': body '" + heavy->name + "' (" +
                         FormatNumber(heavy->mass, 10) + " kg) is " +
                         FormatNumber(heavy->mass / light->mass, 10) + " times as heavy as body '" +
                         light->name + "' (" + FormatNumber(light->mass, 10) +
                         " kg); across a joint at most " + FormatNumber(kMaxJointMassRatio, 10));
  }
  if (!robot_wide) return;
  const Body* heaviest = nullptr;
  const Body* lightest = nullptr;
  for (const Body& b : bodies) {
    if (b.is_static) continue;
    if (heaviest == nullptr || b.mass > heaviest->mass) heaviest = &b;
    if (lightest == nullptr || b.mass < lightest->mass) lightest = &b;
  }
  if (heaviest != nullptr && heaviest->mass > kMaxRobotMassRatio * lightest->mass)
    reader.ErrorAt(lightest->where, "body",
                   "body '" + lightest->name + "' (" + FormatNumber(lightest->mass, 10) +
                       " kg) is " + FormatNumber(heaviest->mass / lightest->mass, 10) +
                       " times lighter than body '" + heaviest->name + "' (" +
                       FormatNumber(heaviest->mass, 10) + " kg); within a robot at most " +
                       FormatNumber(kMaxRobotMassRatio, 10));
}

// Legacy port attribute: integer in (1024, 65535].
std::optional<int> ReadPort(Reader& reader, const xmlNode* node, const std::string& what) {
  const auto text = xml::Attribute(node, "port");
  if (!text) return 0;
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text->c_str(), &end, 10);
  if (text->empty() || *end != '\0' || errno == ERANGE) {
    reader.Error(node, what + ": port '" + *text + "' is not an integer");
    return std::nullopt;
  }
  if (value <= 1024 || value > 65535) {
    reader.Error(node, what + ": port " + *text + " is out of range (1025 to 65535)");
    return std::nullopt;
  }
  return static_cast<int>(value);
}

SensorKind ParseSensorKind(const std::string& type) {
  if (type == "Position") return SensorKind::kPosition;
  if (type == "Scanner") return SensorKind::kScanner;
  if (type == "Velocity") return SensorKind::kVelocity;
  if (type == "ForceTorque") return SensorKind::kForceTorque;
  return SensorKind::kEcho;
}

// Names the robot file declares (the DTD's ID attributes), whether or not
// the element passed its own checks: a reference to a body or joint that is
// there but wrong is not reported a second time as missing.
struct DeclaredNames {
  std::set<std::string> bodies;
  std::set<std::string> joints;
};

std::optional<Sensor> ReadSensor(Reader& reader, const xmlNode* node, const Robot& robot,
                                 const DeclaredNames& declared) {
  Sensor sensor;
  sensor.name = xml::Attribute(node, "name").value_or("");
  sensor.kind = ParseSensorKind(xml::Attribute(node, "type").value_or("Echo"));
  sensor.where = reader.Where(node);
  const std::string what = "sensor '" + sensor.name + "'";
  const size_t errors_before = reader.ErrorCount();
  if (const auto port = ReadPort(reader, node, what)) sensor.port = *port;

  const xmlNode* body_ref = xml::Child(node, "bodyRef");
  const xmlNode* joint_ref = xml::Child(node, "jointRef");
  if (sensor.kind == SensorKind::kForceTorque) {
    if (joint_ref == nullptr) {
      reader.Error(node, what + ": a ForceTorque sensor measures a joint: it needs <jointRef>");
    } else {
      sensor.joint = xml::Text(joint_ref);
      const Joint* joint = robot.FindJoint(sensor.joint);
      if (joint == nullptr && declared.joints.count(sensor.joint) == 0) {
        reader.Error(joint_ref, what + ": '" + sensor.joint + "' is not a joint of robot '" +
                                    robot.model_name + "'");
      } else if (joint != nullptr) {
        sensor.body = joint->body2;
      }
    }
  } else if (body_ref == nullptr) {
    reader.Error(node, what + ": a " + ToString(sensor.kind) + " sensor needs <bodyRef>");
  } else {
    sensor.body = xml::Text(body_ref);
    if (robot.FindBody(sensor.body) == nullptr && declared.bodies.count(sensor.body) == 0)
      reader.Error(body_ref, what + ": '" + sensor.body + "' is not a body of robot '" +
                                 robot.model_name + "'");
  }
  if (const xmlNode* t = xml::Child(node, "transformation")) {
    if (const auto mount = reader.Transformation(t, what + " transformation")) {
      sensor.mount = *mount;
      if (!CoordinatesInRange(mount->translation()))
        reader.Error(t, what + ": mount position " + VectorText(mount->translation()) +
                            " m is out of range: " + CoordinateRangeText());
    }
  }
  if (const xmlNode* rate = xml::Child(node, "rate")) {
    if (const auto r = reader.Number(rate, what + " rate")) {
      if (*r < 0.0 || *r > 10000.0)
        reader.Error(rate, what + ": rate " + FormatNumber(*r, 10) + " Hz is out of range [0, 10000]");
      sensor.rate = *r;
    }
  }
  std::set<std::string> seen;
  for (const xmlNode* p : xml::Children(node, "parameter")) {
    const std::string name = xml::Attribute(p, "name").value_or("");
    if (sensor.kind != SensorKind::kScanner) {
      reader.Error(p, what + ": " + ToString(sensor.kind) + " sensors have no parameter '" +
                          name + "'");
      continue;
    }
    if (!seen.insert(name).second) {
      reader.Error(p, what + ": parameter '" + name + "' is given twice");
      continue;
    }
    const auto value = reader.Number(p, what + " parameter " + name);
    if (!value) continue;
    if (name == "rays") {
      if (*value < 1 || *value > 10000 || *value != std::floor(*value))
        reader.Error(p, what + ": rays must be a whole number from 1 to 10000, got " +
                            FormatNumber(*value, 10));
      else
        sensor.rays = static_cast<int>(*value);
    } else if (name == "halfSpan") {
      if (*value < 0.0 || *value > M_PI)
        reader.Error(p, what + ": halfSpan " + FormatNumber(*value, 10) +
                            " rad is out of range [0, pi]");
      else
        sensor.half_span = *value;
    } else if (name == "range") {
      if (*value <= 0.0 || *value > 1e4)
        reader.Error(p, what + ": range " + FormatNumber(*value, 10) +
                            " m is out of range (0, 10000]");
      else
        sensor.range = *value;
    }
  }
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return sensor;
}

ActuatorKind ParseActuatorKind(const std::string& type) {
  if (type == "AngleController") return ActuatorKind::kAngle;
  if (type == "LinearMotor") return ActuatorKind::kLinearMotor;
  return ActuatorKind::kJointVelocity;
}

std::optional<Actuator> ReadActuator(Reader& reader, const xmlNode* node, const Robot& robot,
                                     const DeclaredNames& declared) {
  Actuator actuator;
  actuator.name = xml::Attribute(node, "name").value_or("");
  actuator.kind = ParseActuatorKind(xml::Attribute(node, "type").value_or(""));
  actuator.where = reader.Where(node);
  const std::string what = "actuator '" + actuator.name + "'";
  const size_t errors_before = reader.ErrorCount();
  if (const auto port = ReadPort(reader, node, what)) actuator.port = *port;
  const xmlNode* joint_ref = xml::Child(node, "jointRef");
  actuator.joint = xml::Text(joint_ref);
  const Joint* joint = robot.FindJoint(actuator.joint);
  if (joint == nullptr) {
    if (declared.joints.count(actuator.joint) == 0)
      reader.Error(joint_ref, what + ": '" + actuator.joint + "' is not a joint of robot '" +
                                  robot.model_name + "'");
  } else {
    const bool rotational = joint->kind == JointKind::kHinge ||
                            joint->kind == JointKind::kUniversal ||
                            joint->kind == JointKind::kHinge2;
    const bool fits = actuator.kind == ActuatorKind::kLinearMotor
                          ? joint->kind == JointKind::kSlider
                          : (actuator.kind == ActuatorKind::kAngle
                                 ? rotational
                                 : (rotational || joint->kind == JointKind::kSlider));
    if (!fits)
      reader.Error(joint_ref, what + ": a " + ToString(actuator.kind) + " cannot drive " +
                                  ToString(joint->kind) + " joint '" + actuator.joint + "'");
  }
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return actuator;
}

// Bodies that no chain of joints reaches from the first body. Judged on
// what the file declares, so that it is reported along with any other
// problem; except when a joint names a body that does not exist or joins a
// body to itself (reported already): then the graph the file means is
// unknown.
void CheckConnected(Reader& reader, const xmlNode* root) {
  const std::vector<const xmlNode*> bodies = xml::Children(root, "body");
  if (bodies.empty()) return;
  std::set<std::string> names;
  for (const xmlNode* b : bodies) names.insert(xml::Attribute(b, "name").value_or(""));
  std::map<std::string, std::vector<std::string>> neighbours;
  for (const xmlNode* j : xml::Children(root, "joint")) {
    const std::string body1 = xml::Text(xml::Child(j, "body1"));
    const std::string body2 = xml::Text(xml::Child(j, "body2"));
    if (names.count(body1) == 0 || names.count(body2) == 0 || body1 == body2) return;
    neighbours[body1].push_back(body2);
    neighbours[body2].push_back(body1);
  }
  const std::string first = xml::Attribute(bodies.front(), "name").value_or("");
  std::set<std::string> reached = {first};
  std::vector<std::string> frontier = {first};
  while (!frontier.empty()) {
    const std::string name = frontier.back();
    frontier.pop_back();
    for (const std::string& next : neighbours[name])
      if (reached.insert(next).second) frontier.push_back(next);
  }
  for (const xmlNode* b : bodies) {
    const std::string name = xml::Attribute(b, "name").value_or("");
    if (reached.count(name) == 0)
      reader.Error(b, "body '" + name + "' is not connected to '" + first +
                          "' by any chain of joints (a robot is one connected graph)");
  }
}

// Legacy ports are TCP ports of one machine: unique within a robot and over
// all robots of a world. used maps each port to its owner. Within a robot
// file (placement null) a clash is reported at the second user; between
// robots (the files are fine each) at the world's <robot> that placed the
// second one.
void CheckUniquePorts(Reader& reader, const Robot& robot, std::map<int, std::string>* used,
                      const xmlNode* placement, const std::string& instance) {
  auto check = [&](int port, const std::string& name, const SourceLocation& where,
                   const char* element) {
    if (port == 0) return;
    const auto [it, inserted] =
        used->emplace(port, placement == nullptr ? name : instance + "/" + name);
    if (inserted) return;
    const std::string what = std::string(element) + " '" + name + "'";
    const std::string clash =
        "port " + std::to_string(port) + " is already used by '" + it->second + "'";
    if (placement == nullptr)
      reader.ErrorAt(where, element, what + ": " + clash);
    else
      reader.Error(placement, "robot '" + instance + "': " + what + " " + clash);
  };
  for (const Sensor& s : robot.sensors) check(s.port, s.name, s.where, "sensor");
  for (const Actuator& a : robot.actuators) check(a.port, a.name, a.where, "actuator");
}

void CheckMaterialNames(Reader& reader, const std::vector<Body>& bodies, const char* element,
                        const std::function<bool(const std::string&)>& exists,
                        const std::string& where_defined) {
  for (const Body& b : bodies) {
    if (!b.material.empty() && !exists(b.material))
      reader.ErrorAt(b.where, element,
                     std::string(element) + " '" + b.name + "': material '" + b.material +
                         "' is not defined in " + where_defined);
  }
}

// A body whose material sets friction along its rolling direction needs an
// axis it rolls about (SpinAxis in model.h says where it comes from).
void CheckRollingBodies(Reader& reader, const std::vector<Body>& bodies,
                        const std::vector<Joint>& joints, const char* element,
                        const std::function<const Material*(const std::string&)>& material_of) {
  for (const Body& b : bodies) {
    const Material* m = b.material.empty() ? nullptr : material_of(b.material);
    if (m == nullptr || m->friction_direction != FrictionDirection::kRolling) continue;
    std::string why;
    if (!SpinAxis(b, joints, &why))
      reader.ErrorAt(b.where, element,
                     std::string(element) + " '" + b.name + "': material '" + m->name + "' (" +
                         m->where.file + ":" + std::to_string(m->where.line) +
                         ") has frictionDirection rolling, but the body has no spin axis: " + why);
  }
}

}  // namespace

namespace {

const char* FileTypeName(mode_t mode) {
  if (S_ISDIR(mode)) return "directory";
  if (S_ISCHR(mode)) return "character device";
  if (S_ISBLK(mode)) return "block device";
  if (S_ISFIFO(mode)) return "FIFO";
  if (S_ISSOCK(mode)) return "socket";
  return "special file";
}

// Closes a file descriptor on every path out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

std::string SizeText(long long bytes) {
  return std::to_string(bytes) + " bytes (" + FormatNumber(static_cast<double>(bytes) / 1048576.0, 10) +
         " MiB)";
}

// Reads a model file through reader; on failure adds a diagnostic at the
// file (the reader's reason when it gave one) and returns false.
bool ReadModelFile(const std::string& path, const FileReader& read, const char* kind,
                   std::string* xml, DiagnosticList* diagnostics) {
  try {
    if (read(path, xml)) return true;
    diagnostics->Add(path, 0, "", std::string("cannot read ") + kind + " file");
  } catch (const ModelFileError& e) {
    diagnostics->Add(path, 0, "",
                     e.cannot_open() ? std::string("cannot read ") + kind + " file: " + e.what()
                                     : std::string(e.what()));
  }
  return false;
}

}  // namespace

bool ReadFileFromDisk(const std::string& path, std::string* contents) {
  // O_NONBLOCK: opening a FIFO without a writer must not wait for one; the
  // type check below refuses it before any read.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) throw ModelFileError(std::strerror(errno), true);
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0)
    throw ModelFileError(std::string("cannot stat: ") + std::strerror(errno), true);
  if (!S_ISREG(info.st_mode))
    throw ModelFileError(std::string("not a regular file (") + FileTypeName(info.st_mode) +
                         "); model files must be regular files",
                         false);
  if (info.st_size > kMaxModelFileBytes)
    throw ModelFileError("file is " + SizeText(info.st_size) + "; model files may have at most " +
                         SizeText(kMaxModelFileBytes),
                         false);
  // Read up to one byte past the limit: a file that grows while it is read
  // is refused too, never read without end.
  contents->clear();
  contents->reserve(static_cast<size_t>(info.st_size));
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw ModelFileError(std::strerror(errno), true);
    }
    if (n == 0) break;
    contents->append(buffer, static_cast<size_t>(n));
    if (static_cast<long long>(contents->size()) > kMaxModelFileBytes)
      throw ModelFileError("file grew beyond " + SizeText(kMaxModelFileBytes) +
                           " while it was read; model files may have at most that",
                           false);
  }
  return true;
}

const std::string& WorldDtd() {
  static const std::string kText(kWorldDtdText);
  return kText;
}

const std::string& RobotDtd() {
  static const std::string kText(kRobotDtdText);
  return kText;
}

RobotLoadResult ParseRobot(const std::string& xml, const std::string& file_name) {
  RobotLoadResult result;
  const std::optional<xml::Document> doc = xml::Document::Read(
      xml, file_name, "robot", xml::Dtd{"robot.dtd", RobotDtd()}, &result.diagnostics);
  if (!doc) return result;
  Reader reader(file_name, &result.diagnostics);
  const xmlNode* root = doc->root();
  Robot robot;
  robot.file = file_name;
  robot.model_name = xml::Attribute(root, "name").value_or("");
  robot.description = xml::Text(xml::Child(root, "description"));
  for (const xmlNode* n : xml::Children(root, "material"))
    if (auto m = ReadMaterial(reader, n)) robot.materials.push_back(*m);
  for (const xmlNode* n : xml::Children(root, "body"))
    if (auto b = ReadBody(reader, n, "body")) robot.bodies.push_back(*b);
  // Body names come from the DTD-validated ID attributes, so a joint that
  // names a body which failed its own checks is judged against all names.
  std::set<std::string> body_names;
  for (const xmlNode* n : xml::Children(root, "body"))
    body_names.insert(xml::Attribute(n, "name").value_or(""));
  const std::string owner = "robot '" + robot.model_name + "'";
  for (const xmlNode* n : xml::Children(root, "joint")) {
    auto joint = ReadJoint(reader, n,
                           [&](const std::string& name) { return body_names.count(name) > 0; },
                           owner);
    if (joint) robot.joints.push_back(*joint);
  }
  DeclaredNames declared;
  declared.bodies = body_names;
  for (const xmlNode* n : xml::Children(root, "joint"))
    declared.joints.insert(xml::Attribute(n, "name").value_or(""));
  for (const xmlNode* n : xml::Children(root, "sensor"))
    if (auto s = ReadSensor(reader, n, robot, declared)) robot.sensors.push_back(*s);
  for (const xmlNode* n : xml::Children(root, "actuator"))
    if (auto a = ReadActuator(reader, n, robot, declared)) robot.actuators.push_back(*a);
  CheckConnected(reader, root);
  // Bodies of the robot's own materials; a world's material of the same
  // name is checked by the world.
  CheckRollingBodies(reader, robot.bodies, robot.joints, "body", [&](const std::string& name) {
    for (const Material& m : robot.materials)
      if (m.name == name) return &m;
    return static_cast<const Material*>(nullptr);
  });
  if (result.diagnostics.empty()) CheckMassRatios(reader, robot.bodies, robot.joints, true);
  std::map<int, std::string> ports;
  CheckUniquePorts(reader, robot, &ports, nullptr, "");
  if (result.diagnostics.empty()) result.robot = std::move(robot);
  return result;
}

RobotLoadResult LoadRobotFile(const std::string& path, const FileReader& read) {
  std::string xml;
  RobotLoadResult result;
  if (!ReadModelFile(path, read, "robot", &xml, &result.diagnostics)) return result;
  return ParseRobot(xml, path);
}

namespace {

// A robot's bodies and joint anchors where the world places them must lie
// within limits::kMaxCoordinate; reported once, at the placing <robot>.
void CheckPlacement(Reader& reader, const xmlNode* robot_node, const RobotInstance& instance) {
  const xmlNode* at = xml::Child(robot_node, "transformation");
  if (at == nullptr) at = robot_node;
  auto report = [&](const std::string& what, const Eigen::Vector3d& where) {
    reader.Error(at, "robot '" + instance.name + "': placed at " +
                         VectorText(instance.placement.translation()) + " m, its " + what +
                         " is at " + VectorText(where) + " m, out of range: " +
                         CoordinateRangeText());
  };
  for (const Body& b : instance.robot.bodies) {
    const Eigen::Vector3d p = instance.placement * b.pose.translation();
    if (!CoordinatesInRange(p)) return report("body '" + b.name + "'", p);
  }
  for (const Joint& j : instance.robot.joints) {
    const Eigen::Vector3d p = instance.placement * j.anchor;
    if (!CoordinatesInRange(p)) return report("joint '" + j.name + "' anchor", p);
  }
}

// Whether loading failed only because the file could not be opened.
bool CannotOpen(const DiagnosticList& diagnostics) {
  return diagnostics.size() == 1 && diagnostics.items()[0].line == 0 &&
         diagnostics.items()[0].message.rfind("cannot read robot file", 0) == 0;
}

}  // namespace

WorldLoadResult ParseWorld(const std::string& xml, const std::string& file_name,
                           const FileReader& read) {
  WorldLoadResult result;
  const std::optional<xml::Document> doc = xml::Document::Read(
      xml, file_name, "world", xml::Dtd{"world.dtd", WorldDtd()}, &result.diagnostics);
  if (!doc) return result;
  Reader reader(file_name, &result.diagnostics);
  const xmlNode* root = doc->root();
  World world;
  world.file = file_name;
  world.name = xml::Attribute(root, "name").value_or("");
  world.description = xml::Text(xml::Child(root, "description"));

  if (const xmlNode* g = xml::Child(root, "gravity")) {
    if (const auto gravity = reader.Vector(g, "gravity")) {
      world.gravity = *gravity;
      if (gravity->norm() > 1e4)
        reader.Error(g, "gravity of magnitude " + FormatNumber(gravity->norm(), 10) +
                            " m/s^2 is not plausible (at most 10000)");
    }
  }
  if (const xmlNode* s = xml::Child(root, "surface")) {
    const auto a = reader.Number(xml::Child(s, "a"), "surface a");
    const auto b = reader.Number(xml::Child(s, "b"), "surface b");
    const auto c = reader.Number(xml::Child(s, "c"), "surface c");
    const auto d = reader.Number(xml::Child(s, "d"), "surface d");
    if (a && b && c && d) {
      const Eigen::Vector3d normal(*a, *b, *c);
      if (normal.norm() < 1e-9) {
        reader.Error(s, "surface normal (a, b, c) has zero length");
      } else {
        world.has_plane = true;
        world.plane << normal / normal.norm(), *d / normal.norm();
      }
    }
    world.plane_material = xml::Attribute(s, "material").value_or("");
  }
  if (const xmlNode* space = xml::Child(root, "collisionSpace")) {
    const std::string type = xml::Attribute(space, "type").value_or("hash");
    world.collision_space = type == "simple"     ? CollisionSpaceKind::kSimple
                            : type == "quadtree" ? CollisionSpaceKind::kQuadTree
                                                 : CollisionSpaceKind::kHash;
  }
  for (const xmlNode* n : xml::Children(root, "material"))
    if (auto m = ReadMaterial(reader, n)) world.materials.push_back(*m);

  if (const xmlNode* h = xml::Child(root, "heightfield")) {
    Heightfield field;
    field.where = reader.Where(h);
    field.material = xml::Attribute(h, "material").value_or("");
    const size_t errors_before = reader.ErrorCount();
    auto count = [&](const char* attribute) -> int {
      const std::string text = xml::Attribute(h, attribute).value_or("");
      char* end = nullptr;
      const long value = std::strtol(text.c_str(), &end, 10);
      if (text.empty() || *end != '\0' || value < 2 || value > 100000) {
        reader.Error(h, std::string("heightfield ") + attribute + " '" + text +
                            "' must be a whole number from 2 to 100000");
        return 0;
      }
      return static_cast<int>(value);
    };
    field.rows = count("rows");
    field.columns = count("columns");
    auto positive = [&](const char* tag) -> double {
      const auto v = reader.Number(xml::Child(h, tag), std::string("heightfield ") + tag);
      if (v && *v <= 0.0)
        reader.Error(xml::Child(h, tag), std::string("heightfield ") + tag +
                                                " must be positive, got " + FormatNumber(*v, 10));
      return v.value_or(0.0);
    };
    field.width = positive("width");
    field.depth = positive("depth");
    for (const char* tag : {"width", "depth"}) {
      const double extent = std::string(tag) == "width" ? field.width : field.depth;
      if (extent > limits::kMaxCoordinate)
        reader.Error(xml::Child(h, tag), std::string("heightfield ") + tag + " " +
                                                FormatNumber(extent, 10) + " m is out of range (0, " +
                                                FormatNumber(limits::kMaxCoordinate, 10) + "] m");
    }
    bool ok = true;
    field.scale = reader.NumberOr(h, "scale", 1.0, "heightfield", &ok);
    field.offset = reader.NumberOr(h, "offset", 0.0, "heightfield", &ok);
    field.thickness = reader.NumberOr(h, "thickness", 1.0, "heightfield", &ok);
    if (field.thickness <= 0.0)
      reader.Error(xml::Child(h, "thickness"), "heightfield thickness must be positive, got " +
                                                      FormatNumber(field.thickness, 10));
    else if (field.thickness > limits::kMaxCoordinate)
      reader.Error(xml::Child(h, "thickness"),
                   "heightfield thickness " + FormatNumber(field.thickness, 10) +
                       " m is out of range (0, " + FormatNumber(limits::kMaxCoordinate, 10) + "] m");
    if (const xmlNode* p = xml::Child(h, "position")) {
      if (const auto position = reader.Vector(p, "heightfield position")) {
        field.position = *position;
        if (!CoordinatesInRange(*position))
          reader.Error(p, "heightfield position " + VectorText(*position) +
                              " m is out of range: " + CoordinateRangeText());
      }
    }
    // Samples fill many lines (with comments between rows): a bad one is
    // reported at its own line, counted from <samples> through the text and
    // the comments, with its row and column.
    const xmlNode* samples = xml::Child(h, "samples");
    int line = reader.Where(samples).line;
    bool bad_sample = false;
    for (const xmlNode* part = samples ? samples->children : nullptr; part && !bad_sample;
         part = part->next) {
      const std::string text = xml::RawText(part);
      if (part->type != XML_TEXT_NODE && part->type != XML_CDATA_SECTION_NODE) {
        line += static_cast<int>(std::count(text.begin(), text.end(), '\n'));
        continue;
      }
      for (size_t i = 0; i < text.size();) {
        if (std::isspace(static_cast<unsigned char>(text[i]))) {
          if (text[i++] == '\n') ++line;
          continue;
        }
        const size_t start = i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        const std::string token = text.substr(start, i - start);
        char* end = nullptr;
        const double value = std::strtod(token.c_str(), &end);
        const bool finite = *end == '\0' && std::isfinite(value);
        // The height ODE builds: offset + scale x sample, in the range of
        // every other coordinate.
        const double height = field.offset + field.scale * value;
        if (!finite || !(std::abs(height) <= limits::kMaxCoordinate)) {
          const size_t index = field.samples.size();
          const std::string place =
              field.columns > 0 ? " (row " + std::to_string(index / field.columns + 1) +
                                      ", column " + std::to_string(index % field.columns + 1) + ")"
                                : "";
          reader.ErrorAt(SourceLocation{reader.file(), line}, "samples",
                         "heightfield sample " + std::to_string(index + 1) + place + " '" +
                             token + "' " +
                             (!finite ? std::string("is not a finite number")
                                      : "gives a height of " + FormatNumber(height, 10) +
                                            " m (offset + scale x sample), out of range: |y| <= " +
                                            FormatNumber(limits::kMaxCoordinate, 10) + " m"));
          bad_sample = true;
          break;
        }
        field.samples.push_back(value);
      }
    }
    const size_t expected = static_cast<size_t>(field.rows) * static_cast<size_t>(field.columns);
    if (reader.ErrorCount() == errors_before && field.samples.size() != expected) {
      reader.Error(samples, "heightfield has " + std::to_string(field.samples.size()) +
                                " samples; rows x columns = " + std::to_string(field.rows) +
                                " x " + std::to_string(field.columns) + " needs " +
                                std::to_string(expected));
    }
    if (reader.ErrorCount() == errors_before) world.heightfield = std::move(field);
  }

  for (const xmlNode* n : xml::Children(root, "object"))
    if (auto b = ReadBody(reader, n, "object")) world.objects.push_back(*b);
  std::set<std::string> object_names;
  for (const xmlNode* n : xml::Children(root, "object"))
    object_names.insert(xml::Attribute(n, "name").value_or(""));
  for (const xmlNode* n : xml::Children(root, "joint")) {
    auto joint = ReadJoint(reader, n,
                           [&](const std::string& name) {
                             return name == kWorldBodyName || object_names.count(name) > 0;
                           },
                           "the world (objects or 'world')");
    if (joint) world.joints.push_back(*joint);
  }
  CheckMassRatios(reader, world.objects, world.joints, false);

  // Robots: each file is loaded and its diagnostics kept as they are
  // (pointing into the robot file), plus one line at the placing element.
  const std::filesystem::path base = std::filesystem::path(file_name).parent_path();
  std::map<int, std::string> ports;
  for (const xmlNode* n : xml::Children(root, "robot")) {
    RobotInstance instance;
    instance.name = xml::Attribute(n, "name").value_or("");
    instance.file = xml::Attribute(n, "file").value_or("");
    instance.where = reader.Where(n);
    const std::filesystem::path path(instance.file);
    instance.resolved_file =
        (path.is_relative() ? (base / path).lexically_normal() : path).string();
    if (const xmlNode* t = xml::Child(n, "transformation")) {
      if (const auto placement =
              reader.Transformation(t, "robot '" + instance.name + "' transformation"))
        instance.placement = *placement;
    }
    RobotLoadResult loaded = LoadRobotFile(instance.resolved_file, read);
    // A world copied away from models/worlds still finds the shipped
    // robots: a relative robot path's file name is tried in each data
    // root's models/robots/ too.
    std::vector<std::string> also_tried;
    if (!loaded.robot && path.is_relative() && CannotOpen(loaded.diagnostics)) {
      for (const DataRoot& root : DataRoots()) {
        const std::string candidate =
            (std::filesystem::path(root.directory) / "models/robots" / path.filename())
                .lexically_normal()
                .string();
        if (candidate == instance.resolved_file) continue;
        RobotLoadResult other = LoadRobotFile(candidate, read);
        if (!CannotOpen(other.diagnostics)) {
          instance.resolved_file = candidate;
          loaded = std::move(other);
          break;
        }
        also_tried.push_back(candidate + " (" + root.source + ")");
      }
    }
    if (!loaded.robot) {
      std::string tried;
      for (const std::string& t : also_tried) tried += (tried.empty() ? "" : ", ") + t;
      if (!tried.empty()) tried = "; also looked for it at " + tried;
      reader.Error(n, "robot '" + instance.name + "': cannot load '" + instance.file + "' (" +
                          std::to_string(loaded.diagnostics.size()) + " problem" +
                          (loaded.diagnostics.size() == 1 ? "" : "s") + ")" + tried);
      result.diagnostics.Append(loaded.diagnostics);
      continue;
    }
    instance.robot = std::move(*loaded.robot);
    CheckPlacement(reader, n, instance);
    CheckUniquePorts(reader, instance.robot, &ports, n, instance.name);
    world.robots.push_back(std::move(instance));
  }

  // Materials: robots may define their own; the world's definitions win.
  for (const RobotInstance& r : world.robots) {
    for (const Material& m : r.robot.materials)
      if (world.FindMaterial(m.name) == nullptr) world.materials.push_back(m);
  }
  // A material whose values are wrong is reported as such, not as missing.
  std::set<std::string> declared_materials;
  for (const xmlNode* n : xml::Children(root, "material"))
    declared_materials.insert(xml::Attribute(n, "name").value_or(""));
  auto material_exists = [&](const std::string& name) {
    return world.FindMaterial(name) != nullptr || declared_materials.count(name) > 0;
  };
  CheckMaterialNames(reader, world.objects, "object", material_exists, "the world");
  for (const RobotInstance& r : world.robots)
    CheckMaterialNames(reader, r.robot.bodies, "body", material_exists, "the world or the robot");
  auto world_material = [&](const std::string& name) { return world.FindMaterial(name); };
  CheckRollingBodies(reader, world.objects, world.joints, "object", world_material);
  for (const RobotInstance& r : world.robots) {
    CheckRollingBodies(reader, r.robot.bodies, r.robot.joints, "body",
                       [&](const std::string& name) {
                         // The robot's own materials were checked with it.
                         return declared_materials.count(name) > 0 ? world.FindMaterial(name)
                                                                   : nullptr;
                       });
  }
  if (!world.plane_material.empty() && !material_exists(world.plane_material))
    reader.Error(xml::Child(root, "surface"),
                 "surface material '" + world.plane_material + "' is not defined");
  if (world.heightfield && !world.heightfield->material.empty() &&
      !material_exists(world.heightfield->material))
    reader.Error(xml::Child(root, "heightfield"),
                 "heightfield material '" + world.heightfield->material + "' is not defined");

  if (result.diagnostics.empty()) result.world = std::move(world);
  return result;
}

WorldLoadResult LoadWorldFile(const std::string& path, const FileReader& read) {
  std::string xml;
  WorldLoadResult result;
  if (!ReadModelFile(path, read, "world", &xml, &result.diagnostics)) return result;
  return ParseWorld(xml, path, read);
}

std::string FindWorldFile(const std::string& name) {
  return FindDataFile(name, "world", {"models/worlds"});
}

std::string FindRobotFile(const std::string& name) {
  return FindDataFile(name, "robot", {"models/robots"});
}

World LoadWorldOrThrow(const std::string& path) {
  WorldLoadResult result = LoadWorldFile(FindWorldFile(path));
  if (!result.world) throw ModelError(result.diagnostics);
  return std::move(*result.world);
}

Robot LoadRobotOrThrow(const std::string& path) {
  RobotLoadResult result = LoadRobotFile(FindRobotFile(path));
  if (!result.robot) throw ModelError(result.diagnostics);
  return std::move(*result.robot);
}

std::string DescribeWorld(const World& world) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(3);
  out << "world '" << world.name << "' (" << world.file << ")\n";
  out << "  gravity " << world.gravity.x() << " " << world.gravity.y() << " "
      << world.gravity.z() << " m/s^2, collision space " << ToString(world.collision_space)
      << (world.has_plane ? ", ground plane" : "")
      << (world.heightfield ? ", heightfield " + std::to_string(world.heightfield->rows) + "x" +
                                  std::to_string(world.heightfield->columns)
                            : std::string())
      << "\n";
  double object_mass = 0.0;
  for (const Body& b : world.objects) object_mass += b.mass;
  out << "  objects: " << world.objects.size() << " (" << object_mass << " kg), joints: "
      << world.joints.size() << ", materials: " << world.materials.size() << "\n";
  for (const RobotInstance& r : world.robots) {
    out << "  robot '" << r.name << "' = " << r.robot.model_name << " (" << r.resolved_file
        << ")\n";
    out << "    bodies: " << r.robot.bodies.size() << ", joints: " << r.robot.joints.size()
        << ", sensors: " << r.robot.sensors.size() << ", actuators: "
        << r.robot.actuators.size() << ", total mass: " << r.robot.TotalMass() << " kg\n";
  }
  return out.str();
}

}  // namespace simpartner::model
