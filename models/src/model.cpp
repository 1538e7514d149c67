#include "simpartner/model/model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "simpartner/rotation_between.h"

namespace simpartner::model {

const char* ToString(GeometryKind kind) {
  switch (kind) {
    case GeometryKind::kNone: return "Body";
    case GeometryKind::kBox: return "Box";
    case GeometryKind::kSphere: return "Sphere";
    case GeometryKind::kCylinder: return "Cylinder";
    case GeometryKind::kCapsule: return "Capsule";
  }
  return "?";
}

const char* ToString(JointKind kind) {
  switch (kind) {
    case JointKind::kFixed: return "Fixed";
    case JointKind::kHinge: return "Hinge";
    case JointKind::kSlider: return "Slider";
    case JointKind::kBall: return "Ball";
    case JointKind::kUniversal: return "Universal";
    case JointKind::kHinge2: return "Hinge2";
  }
  return "?";
}

const char* ToString(SensorKind kind) {
  switch (kind) {
    case SensorKind::kEcho: return "Echo";
    case SensorKind::kPosition: return "Position";
    case SensorKind::kScanner: return "Scanner";
    case SensorKind::kVelocity: return "Velocity";
    case SensorKind::kForceTorque: return "ForceTorque";
    case SensorKind::kImu: return "Imu";
    case SensorKind::kGnss: return "Gnss";
    case SensorKind::kEncoder: return "Encoder";
    case SensorKind::kLidar: return "Lidar";
    case SensorKind::kContact: return "Contact";
    case SensorKind::kCamera: return "Camera";
  }
  return "?";
}

const char* ToString(ActuatorKind kind) {
  switch (kind) {
    case ActuatorKind::kJointVelocity: return "JointController";
    case ActuatorKind::kAngle: return "AngleController";
    case ActuatorKind::kLinearMotor: return "LinearMotor";
  }
  return "?";
}

const char* ToString(CollisionSpaceKind kind) {
  switch (kind) {
    case CollisionSpaceKind::kSimple: return "simple";
    case CollisionSpaceKind::kHash: return "hash";
    case CollisionSpaceKind::kQuadTree: return "quadtree";
  }
  return "?";
}

const char* ToString(FrictionDirection direction) {
  switch (direction) {
    case FrictionDirection::kSlip: return "slip";
    case FrictionDirection::kRolling: return "rolling";
  }
  return "?";
}

const char* ToString(CameraDepth depth) {
  switch (depth) {
    case CameraDepth::kNone: return "none";
    case CameraDepth::kMetres: return "metres";
    case CameraDepth::kMillimetres: return "millimetres";
  }
  return "?";
}

std::optional<Eigen::Vector3d> SpinAxis(const Body& body, const std::vector<Joint>& joints,
                                        std::string* why) {
  // A hinge turns the body about its axis whatever its shape, so it wins
  // over the geometry; the axis is fixed in the body frame.
  std::vector<const Joint*> hinges;
  std::vector<Eigen::Vector3d> axes;
  for (const Joint& j : joints) {
    if (j.kind == JointKind::kHinge && (j.body1 == body.name || j.body2 == body.name)) {
      hinges.push_back(&j);
      axes.push_back(j.axis[0]);
    } else if (j.kind == JointKind::kHinge2 && j.body2 == body.name) {
      hinges.push_back(&j);
      axes.push_back(j.axis[1]);
    }
  }
  if (hinges.size() == 1) return (body.pose.linear().transpose() * axes[0]).normalized();
  if (body.geometry.kind == GeometryKind::kCylinder || body.geometry.kind == GeometryKind::kCapsule)
    return Eigen::Vector3d::UnitZ();
  if (why != nullptr) {
    if (hinges.empty()) {
      *why = "no Hinge joins it and it is a " + std::string(ToString(body.geometry.kind)) +
             ", not a Cylinder or Capsule";
    } else {
      std::string names;
      for (const Joint* j : hinges) names += (names.empty() ? "" : ", ") + j->name;
      *why = std::to_string(hinges.size()) + " hinges join it (" + names + ") and it is a " +
             ToString(body.geometry.kind) + ", not a Cylinder or Capsule";
    }
  }
  return std::nullopt;
}

int AxisCount(JointKind kind) {
  switch (kind) {
    case JointKind::kFixed: return 0;
    case JointKind::kHinge: return 1;
    case JointKind::kSlider: return 1;
    case JointKind::kBall: return 0;
    case JointKind::kUniversal: return 2;
    case JointKind::kHinge2: return 2;
  }
  return 0;
}

Joint::Joint() {
  std::fill(std::begin(lo_stop), std::end(lo_stop), -std::numeric_limits<double>::infinity());
  std::fill(std::begin(hi_stop), std::end(hi_stop), std::numeric_limits<double>::infinity());
}

double Robot::TotalMass() const {
  double total = 0.0;
  for (const Body& b : bodies) total += b.mass;
  return total;
}

const Body* Robot::FindBody(const std::string& name) const {
  for (const Body& b : bodies)
    if (b.name == name) return &b;
  return nullptr;
}

const Joint* Robot::FindJoint(const std::string& name) const {
  for (const Joint& j : joints)
    if (j.name == name) return &j;
  return nullptr;
}

double Heightfield::HeightAt(double x, double z) const {
  if (rows < 2 || columns < 2 || samples.size() != static_cast<size_t>(rows) * columns)
    return offset;
  const double u = std::clamp((x + width / 2.0) / width, 0.0, 1.0) * (columns - 1);
  const double v = std::clamp((z + depth / 2.0) / depth, 0.0, 1.0) * (rows - 1);
  const int c0 = std::min(static_cast<int>(u), columns - 2);
  const int r0 = std::min(static_cast<int>(v), rows - 2);
  const double fu = u - c0;
  const double fv = v - r0;
  auto at = [this](int r, int c) { return samples[static_cast<size_t>(r) * columns + c]; };
  const double top = at(r0, c0) * (1 - fu) + at(r0, c0 + 1) * fu;
  const double bottom = at(r0 + 1, c0) * (1 - fu) + at(r0 + 1, c0 + 1) * fu;
  return scale * (top * (1 - fv) + bottom * fv) + offset;
}

Eigen::Vector3d World::Up() const {
  const double norm = gravity.norm();
  if (norm == 0.0) return Eigen::Vector3d::UnitY();
  return -gravity / norm;
}

Eigen::Isometry3d World::HeightfieldPose() const {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (!heightfield) return pose;
  pose.linear() =
      RotationBetween(Eigen::Vector3d::UnitY(), Up()).toRotationMatrix();
  pose.translation() = heightfield->position;
  return pose;
}

const Material* World::FindMaterial(const std::string& name) const {
  for (const Material& m : materials)
    if (m.name == name) return &m;
  return nullptr;
}

const SoilParameters* World::FindSoil(const std::string& material) const {
  const Material* m = material.empty() ? nullptr : FindMaterial(material);
  return m != nullptr && m->soil ? &*m->soil : nullptr;
}

bool World::HasSoilGround() const {
  return (has_plane && FindSoil(plane_material) != nullptr) ||
         (heightfield && FindSoil(heightfield->material) != nullptr);
}

Eigen::Matrix3d SolidInertia(const Geometry& geometry, double mass) {
  const Eigen::Vector3d& s = geometry.size;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  switch (geometry.kind) {
    case GeometryKind::kNone: {
      const double r = 0.1;
      inertia.diagonal().setConstant(0.4 * mass * r * r);
      break;
    }
    case GeometryKind::kBox:
      inertia(0, 0) = mass / 12.0 * (s.y() * s.y() + s.z() * s.z());
      inertia(1, 1) = mass / 12.0 * (s.x() * s.x() + s.z() * s.z());
      inertia(2, 2) = mass / 12.0 * (s.x() * s.x() + s.y() * s.y());
      break;
    case GeometryKind::kSphere:
      inertia.diagonal().setConstant(0.4 * mass * s.x() * s.x());
      break;
    case GeometryKind::kCylinder: {
      const double r = s.x(), l = s.y();
      inertia(0, 0) = inertia(1, 1) = mass * (3 * r * r + l * l) / 12.0;
      inertia(2, 2) = 0.5 * mass * r * r;
      break;
    }
    case GeometryKind::kCapsule: {
      // Uniform density over a cylinder of length l and two hemispheres.
      const double r = s.x(), l = s.y();
      const double v_cyl = M_PI * r * r * l;
      const double v_sph = 4.0 / 3.0 * M_PI * r * r * r;
      const double m_cyl = mass * v_cyl / (v_cyl + v_sph);
      const double m_sph = mass - m_cyl;
      const double axial = 0.5 * m_cyl * r * r + 0.4 * m_sph * r * r;
      const double transverse = m_cyl * (3 * r * r + l * l) / 12.0 +
                                m_sph * (0.4 * r * r + l * l / 4.0 + 3.0 * l * r / 8.0);
      inertia(0, 0) = inertia(1, 1) = transverse;
      inertia(2, 2) = axial;
      break;
    }
  }
  return inertia;
}

}  // namespace simpartner::model
