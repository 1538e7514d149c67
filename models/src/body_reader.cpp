// <body> (robot) and <object> (world): mass, shape, inertia, pose and
// initial velocity, then the physical ranges (models/README.md, "Physical
// ranges"), each problem at the line of the element that sets the value.
#include <Eigen/Eigenvalues>

#include "parts.h"
#include "simpartner/text.h"

namespace simpartner::model::detail {
namespace {

GeometryKind ParseGeometryKind(const std::string& type) {
  if (type == "Box") return GeometryKind::kBox;
  if (type == "Sphere") return GeometryKind::kSphere;
  if (type == "Cylinder") return GeometryKind::kCylinder;
  if (type == "Capsule") return GeometryKind::kCapsule;
  return GeometryKind::kNone;
}

class BodyReading {
 public:
  BodyReading(Reader& reader, const xmlNode* node, Body* body, const std::string& what)
      : reader_(reader), node_(node), body_(*body), what_(what) {}

  void ReadMass() {
    const xmlNode* mass = xml::Child(node_, "mass");
    if (mass != nullptr) {
      if (const auto m = reader_.Number(mass, what_ + " mass")) {
        if (*m <= 0.0)
          reader_.Error(mass, what_ + ": mass must be positive, got " + FormatNumber(*m, 10));
        body_.mass = *m;
      }
    } else if (!body_.is_static) {
      reader_.Error(node_, what_ + ": a moving body needs <mass>");
    }
  }

  // The dimensions the shape has, and none it does not have.
  void ReadShape() {
    const xmlNode* size = xml::Child(node_, "size");
    const xmlNode* radius = xml::Child(node_, "radius");
    const xmlNode* length = xml::Child(node_, "length");
    Geometry& g = body_.geometry;
    switch (g.kind) {
      case GeometryKind::kNone:
        Forbid(size, "size");
        Forbid(radius, "radius");
        Forbid(length, "length");
        if (body_.is_static) reader_.Error(node_, what_ + ": a static object needs a shape");
        break;
      case GeometryKind::kBox:
        ReadBoxSize(size);
        Forbid(radius, "radius");
        Forbid(length, "length");
        break;
      case GeometryKind::kSphere:
        if (radius == nullptr) reader_.Error(node_, what_ + ": a Sphere needs <radius>");
        else g.size.x() = Positive(radius, "radius");
        Forbid(size, "size");
        Forbid(length, "length");
        break;
      case GeometryKind::kCylinder:
      case GeometryKind::kCapsule:
        if (radius == nullptr || length == nullptr) {
          reader_.Error(node_, what_ + ": a " + ToString(g.kind) + " needs <radius> and <length>");
        } else {
          g.size.x() = Positive(radius, "radius");
          g.size.y() = Positive(length, "length");
        }
        Forbid(size, "size");
        break;
    }
  }

  void ReadInertia() {
    if (const xmlNode* com = xml::Child(node_, "centerOfMass")) {
      if (const auto c = reader_.Vector(com, what_ + " centerOfMass")) body_.com = *c;
    }
    const xmlNode* inertia = xml::Child(node_, "inertia");
    if (inertia == nullptr) return;
    bool ok = true;
    auto moment = [&](const char* name) {
      return reader_.NumberOr(inertia, name, 0.0, what_ + " inertia", &ok);
    };
    const double ixx = moment("Ixx"), iyy = moment("Iyy"), izz = moment("Izz");
    const double ixy = moment("Ixy"), ixz = moment("Ixz"), iyz = moment("Iyz");
    if (!ok) return;
    body_.inertia << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
    body_.inertia_given = true;
    CheckInertiaIsPhysical(inertia);
  }

  void ReadPoseAndVelocity() {
    if (const auto pose = reader_.Transformation(xml::Child(node_, "transformation"),
                                                 what_ + " transformation")) {
      body_.pose = *pose;
    }
    if (const xmlNode* v = xml::Child(node_, "translationalVelocity")) {
      if (const auto value = reader_.Vector(v, "vx", "vy", "vz", what_ + " translationalVelocity"))
        body_.linear_velocity = *value;
    }
    if (const xmlNode* w = xml::Child(node_, "rotationalVelocity")) {
      if (const auto value =
              reader_.Vector(w, "omegax", "omegay", "omegaz", what_ + " rotationalVelocity"))
        body_.angular_velocity = *value;
    }
  }

 private:
  double Positive(const xmlNode* n, const std::string& field) {
    const auto v = reader_.Number(n, what_ + " " + field);
    if (!v) return 0.0;
    if (*v <= 0.0)
      reader_.Error(n, what_ + ": " + field + " must be positive, got " + FormatNumber(*v, 10));
    return *v;
  }

  void Forbid(const xmlNode* n, const char* field) {
    if (n != nullptr)
      reader_.Error(n, what_ + ": a " + ToString(body_.geometry.kind) + " has no <" + field + ">");
  }

  void ReadBoxSize(const xmlNode* size) {
    if (size == nullptr) {
      reader_.Error(node_, what_ + ": a Box needs <size>");
      return;
    }
    const auto s = reader_.Vector(size, what_ + " size");
    if (!s) return;
    for (int i = 0; i < 3; ++i) {
      if ((*s)[i] <= 0.0)
        reader_.Error(size, what_ + ": size " + "xyz"[i] + " must be positive, got " +
                                FormatNumber((*s)[i], 10));
    }
    body_.geometry.size = *s;
  }

  // A physical inertia tensor is positive definite and its principal
  // moments obey the triangle inequality.
  void CheckInertiaIsPhysical(const xmlNode* inertia) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(body_.inertia);
    const Eigen::Vector3d p = solver.eigenvalues();
    const double tolerance = 1e-9 * p.cwiseAbs().maxCoeff();
    const std::string moments =
        FormatNumber(p[0], 10) + ", " + FormatNumber(p[1], 10) + ", " + FormatNumber(p[2], 10);
    if (p.minCoeff() <= 0.0) {
      reader_.Error(inertia, what_ + ": inertia is not positive definite (principal moments " +
                                 moments + ")");
    } else if (p[0] + p[1] < p[2] - tolerance) {
      reader_.Error(inertia, what_ + ": principal moments " + moments +
                                 " break the triangle inequality (no real body has them)");
    }
  }

  Reader& reader_;
  const xmlNode* node_;
  Body& body_;
  const std::string what_;
};

// The ranges of one body that has read without problems.
class BodyRanges {
 public:
  BodyRanges(Reader& reader, const xmlNode* node, const Body& body, const std::string& what)
      : reader_(reader), node_(node), body_(body), what_(what) {}

  void CheckMassAndSize() {
    using namespace limits;
    if (!body_.is_static && (body_.mass < kMinMass || body_.mass > kMaxMass)) {
      reader_.Error(At("mass"), what_ + ": mass " + FormatNumber(body_.mass, 10) +
                                    " kg is out of range " + Range(kMinMass, kMaxMass, " kg"));
    }
    const Geometry& g = body_.geometry;
    switch (g.kind) {
      case GeometryKind::kNone: break;
      case GeometryKind::kBox:
        for (int i = 0; i < 3; ++i) Size(g.size[i], "size", std::string("size ") + "xyz"[i]);
        break;
      case GeometryKind::kSphere: Size(g.size.x(), "radius", "radius"); break;
      case GeometryKind::kCylinder:
      case GeometryKind::kCapsule:
        Size(g.size.x(), "radius", "radius");
        Size(g.size.y(), "length", "length");
        break;
    }
  }

  void CheckPlaceAndMotion() {
    using namespace limits;
    if (!CoordinatesInRange(body_.pose.translation()))
      reader_.Error(At("transformation"), what_ + ": position " +
                                              VectorText(body_.pose.translation()) +
                                              " m is out of range: " + CoordinateRangeText());
    if (!CoordinatesInRange(body_.com))
      reader_.Error(At("centerOfMass"), what_ + ": centerOfMass " + VectorText(body_.com) +
                                            " m is out of range: " + CoordinateRangeText());
    if (body_.linear_velocity.norm() > kMaxLinearSpeed)
      reader_.Error(At("translationalVelocity"),
                    what_ + ": translationalVelocity " + VectorText(body_.linear_velocity) +
                        " m/s is out of range: speed at most " +
                        FormatNumber(kMaxLinearSpeed, 10) + " m/s");
    if (body_.angular_velocity.norm() > kMaxAngularSpeed)
      reader_.Error(At("rotationalVelocity"),
                    what_ + ": rotationalVelocity " + VectorText(body_.angular_velocity) +
                        " rad/s is out of range: rotation at most " +
                        FormatNumber(kMaxAngularSpeed, 10) + " rad/s");
  }

  // Inertia: of the file, or of the solid when computed (then a problem
  // comes from the mass and size, so it is reported at the body).
  void CheckInertia() {
    using namespace limits;
    const xmlNode* at = body_.inertia_given ? At("inertia") : node_;
    const std::string source =
        body_.inertia_given
            ? ""
            : " (of a uniform " + std::string(ToString(body_.geometry.kind)) + " of this mass and size)";
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(body_.inertia);
    const Eigen::Vector3d moments = solver.eigenvalues();
    const double smallest = moments.minCoeff(), largest = moments.maxCoeff();
    const std::string prefix =
        what_ + ": principal moments of inertia " + VectorText(moments) + " kg m^2" + source;
    if (smallest < kMinMoment || largest > kMaxMoment) {
      reader_.Error(at, prefix + " are out of range " + Range(kMinMoment, kMaxMoment, " kg m^2"));
    } else if (largest > kMaxInertiaRatio * smallest) {
      reader_.Error(at, prefix + " differ by a factor of " + FormatNumber(largest / smallest, 10) +
                            "; at most " + FormatNumber(kMaxInertiaRatio, 10));
    }
  }

 private:
  const xmlNode* At(const char* name) const {
    const xmlNode* child = xml::Child(node_, name);
    return child != nullptr ? child : node_;
  }

  void Size(double value, const char* element, const std::string& field) {
    using namespace limits;
    if (value < kMinSize || value > kMaxSize)
      reader_.Error(At(element), what_ + ": " + field + " " + FormatNumber(value, 10) +
                                     " m is out of range " + Range(kMinSize, kMaxSize, " m"));
  }

  Reader& reader_;
  const xmlNode* node_;
  const Body& body_;
  const std::string what_;
};

void CheckBodyRanges(Reader& reader, const xmlNode* node, const Body& body,
                     const std::string& what) {
  const size_t errors_before = reader.ErrorCount();
  BodyRanges ranges(reader, node, body, what);
  ranges.CheckMassAndSize();
  ranges.CheckPlaceAndMotion();
  if (body.is_static || reader.ErrorCount() != errors_before) return;
  ranges.CheckInertia();
}

}  // namespace

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
  BodyReading reading(reader, node, &body, what);
  reading.ReadMass();
  reading.ReadShape();
  reading.ReadInertia();
  reading.ReadPoseAndVelocity();
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  if (!body.inertia_given) body.inertia = SolidInertia(body.geometry, body.mass);
  CheckBodyRanges(reader, node, body, what);
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return body;
}

}  // namespace simpartner::model::detail
