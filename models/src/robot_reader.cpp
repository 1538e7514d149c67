// A robot file: its materials, bodies and joints, the sensors and
// actuators on them, then the checks of the robot as a whole.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include "parts.h"
#include "simpartner/model/sensor_budget.h"
#include "simpartner/model/sensor_parameters.h"
#include "simpartner/text.h"

namespace simpartner::model {
namespace {

using detail::Reader;

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
  if (type == "Imu") return SensorKind::kImu;
  if (type == "Gnss") return SensorKind::kGnss;
  if (type == "Encoder") return SensorKind::kEncoder;
  if (type == "Lidar") return SensorKind::kLidar;
  if (type == "Contact") return SensorKind::kContact;
  if (type == "Camera") return SensorKind::kCamera;
  return SensorKind::kEcho;
}

ActuatorKind ParseActuatorKind(const std::string& type) {
  if (type == "AngleController") return ActuatorKind::kAngle;
  if (type == "LinearMotor") return ActuatorKind::kLinearMotor;
  return ActuatorKind::kJointVelocity;
}

// Names the robot file declares (the DTD's ID attributes), whether or not
// the element passed its own checks: a reference to a body or joint that is
// there but wrong is not reported a second time as missing.
struct DeclaredNames {
  std::set<std::string> bodies;
  std::set<std::string> joints;
};

// What a sensor measures: a joint (force/torque and encoder, at the
// joint's second body) or a body (every other kind).
void ReadSensorTarget(Reader& reader, const xmlNode* node, const Robot& robot,
                      const DeclaredNames& declared, const std::string& what, Sensor* sensor) {
  const xmlNode* body_ref = xml::Child(node, "bodyRef");
  const xmlNode* joint_ref = xml::Child(node, "jointRef");
  if (MeasuresJoint(sensor->kind)) {
    if (joint_ref == nullptr) {
      const char* article = sensor->kind == SensorKind::kEncoder ? "an " : "a ";
      reader.Error(node, what + ": " + article + ToString(sensor->kind) +
                             " sensor measures a joint: it needs <jointRef>");
      return;
    }
    sensor->joint = xml::Text(joint_ref);
    const Joint* joint = robot.FindJoint(sensor->joint);
    if (joint == nullptr && declared.joints.count(sensor->joint) == 0) {
      reader.Error(joint_ref, what + ": '" + sensor->joint + "' is not a joint of robot '" +
                                  robot.model_name + "'");
    } else if (joint != nullptr && sensor->kind == SensorKind::kEncoder &&
               joint->kind != JointKind::kHinge) {
      reader.Error(joint_ref, what + ": an Encoder counts the turns of a Hinge; '" +
                                  sensor->joint + "' is a " + ToString(joint->kind) + " joint");
    } else if (joint != nullptr) {
      sensor->body = joint->body2;
    }
  } else if (body_ref == nullptr) {
    reader.Error(node, what + ": a " + ToString(sensor->kind) + " sensor needs <bodyRef>");
  } else {
    sensor->body = xml::Text(body_ref);
    if (robot.FindBody(sensor->body) == nullptr && declared.bodies.count(sensor->body) == 0)
      reader.Error(body_ref, what + ": '" + sensor->body + "' is not a body of robot '" +
                                 robot.model_name + "'");
  }
}

void ReadSensorMountAndRate(Reader& reader, const xmlNode* node, const std::string& what,
                            Sensor* sensor) {
  if (const xmlNode* t = xml::Child(node, "transformation")) {
    if (const auto mount = reader.Transformation(t, what + " transformation")) {
      sensor->mount = *mount;
      if (!detail::CoordinatesInRange(mount->translation()))
        reader.Error(t, what + ": mount position " + detail::VectorText(mount->translation()) +
                            " m is out of range: " + detail::CoordinateRangeText());
    }
  }
  if (const xmlNode* rate = xml::Child(node, "rate")) {
    if (const auto r = reader.Number(rate, what + " rate")) {
      if (*r < 0.0 || *r > 10000.0)
        reader.Error(rate, what + ": rate " + FormatNumber(*r, 10) + " Hz is out of range [0, 10000]");
      sensor->rate = *r;
    }
  }
}

// One scanner <parameter>: rays, halfSpan or range.
void SetScannerParameter(Reader& reader, const xmlNode* p, const std::string& name, double value,
                         const std::string& what, Sensor* sensor) {
  if (name == "rays") {
    if (value < 1 || value > 10000 || value != std::floor(value))
      reader.Error(p, what + ": rays must be a whole number from 1 to 10000, got " +
                          FormatNumber(value, 10));
    else
      sensor->rays = static_cast<int>(value);
  } else if (name == "halfSpan") {
    if (value < 0.0 || value > M_PI)
      reader.Error(p, what + ": halfSpan " + FormatNumber(value, 10) + " rad is out of range [0, pi]");
    else
      sensor->half_span = value;
  } else if (name == "range") {
    if (value <= 0.0 || value > 1e4)
      reader.Error(p, what + ": range " + FormatNumber(value, 10) + " m is out of range (0, 10000]");
    else
      sensor->range = value;
  }
}

// One parameter of a kind with a table (sensor_parameters.h), checked
// against its range.
void SetTableParameter(Reader& reader, const xmlNode* p, int index, double value,
                       const std::string& what, Sensor* sensor) {
  const SensorParameterSpec& spec = SensorParameterSpecs(sensor->kind)[static_cast<size_t>(index)];
  const std::string unit = *spec.unit ? std::string(" ") + spec.unit : "";
  const bool below = spec.min_open ? value <= spec.min : value < spec.min;
  if (below || value > spec.max) {
    reader.Error(p, what + ": " + spec.name + " " + FormatNumber(value, 10) + unit +
                        " is out of range " + (spec.min_open ? "(" : "[") +
                        FormatNumber(spec.min, 10) + ", " + FormatNumber(spec.max, 10) + "]");
  } else if (spec.whole && value != std::floor(value)) {
    reader.Error(p, what + ": " + spec.name + " must be a whole number, got " +
                        FormatNumber(value, 10));
  } else {
    sensor->parameters[static_cast<size_t>(index)] = value;
  }
}

// Whether a sensor of this kind has the <parameter> called `name` (the
// DTD allows every kind's names on every sensor).
bool TakesParameter(SensorKind kind, const std::string& name) {
  static const std::set<std::string> kScanner{"rays", "halfSpan", "range"};
  static const std::set<std::string> kCamera{"width", "height", "fov", "near", "far", "depth"};
  if (kind == SensorKind::kScanner) return kScanner.count(name) > 0;
  if (kind == SensorKind::kCamera) return kCamera.count(name) > 0;
  return false;
}

std::optional<CameraDepth> ParseCameraDepth(const std::string& text) {
  for (CameraDepth d : {CameraDepth::kNone, CameraDepth::kMetres, CameraDepth::kMillimetres})
    if (text == ToString(d)) return d;
  return std::nullopt;
}

// One camera <parameter>: the image side in whole pixels up to what can be
// rendered, a field of view short of 180 degrees, a positive near distance.
void SetCameraParameter(Reader& reader, const xmlNode* p, const std::string& name,
                        const std::string& what, CameraSettings* camera) {
  if (name == "depth") {
    const std::string text = Trim(xml::Text(p));
    if (const auto depth = ParseCameraDepth(text))
      camera->depth = *depth;
    else
      reader.Error(p, what + ": depth '" + text + "' is not one of none, metres, millimetres");
    return;
  }
  const auto value = reader.Number(p, what + " parameter " + name);
  if (!value) return;
  const double v = *value;
  if (name == "width" || name == "height") {
    if (v < 1 || v > kMaxCameraSide || v != std::floor(v))
      reader.Error(p, what + ": " + name + " must be a whole number of pixels from 1 to " +
                          std::to_string(kMaxCameraSide) + " (the largest image rendered), got " +
                          FormatNumber(v, 10));
    else
      (name == "width" ? camera->width : camera->height) = static_cast<int>(v);
  } else if (name == "fov") {
    if (v <= 0.0 || v >= M_PI)
      reader.Error(p, what + ": fov " + FormatNumber(v, 10) + " rad (" +
                          FormatNumber(v * 180 / M_PI, 6) +
                          " deg) is out of range: a horizontal field of view is above 0 and below "
                          "pi rad (180 deg)");
    else
      camera->fov = v;
  } else if (name == "near" || name == "far") {
    if (v < kMinCameraNear || v > 1e6)
      reader.Error(p, what + ": " + name + " " + FormatNumber(v, 10) +
                          " m is out of range [" + FormatNumber(kMinCameraNear, 10) +
                          ", 1e6]");
    else
      (name == "near" ? camera->near : camera->far) = v;
  }
}

// What a camera's parameters say together: far beyond near, a frame rate,
// and no more pixels a second than the bus carries.
void CheckCamera(Reader& reader, const xmlNode* node, const std::string& what,
                 const Sensor& sensor) {
  const CameraSettings& c = sensor.camera;
  if (c.far <= c.near)
    reader.Error(node, what + ": far " + FormatNumber(c.far, 10) + " m is not beyond near " +
                           FormatNumber(c.near, 10) + " m");
  if (sensor.rate <= 0.0)
    reader.Error(node, what + ": a Camera needs a <rate> above 0 Hz (frames a second of sim time)");
  const double pixels = sensor.rate * c.width * c.height;
  if (pixels > kMaxCameraPixelsPerSecond)
    reader.Error(node, what + ": rate " + FormatNumber(sensor.rate, 10) + " Hz x " +
                           std::to_string(c.width) + " x " + std::to_string(c.height) +
                           " pixels = " + FormatNumber(pixels, 10) + " pixels/s is more than the " +
                           FormatNumber(kMaxCameraPixelsPerSecond, 10) +
                           " pixels/s a camera may send (models/.../model.h says why)");
}

void ReadSensorParameters(Reader& reader, const xmlNode* node, const std::string& what,
                          Sensor* sensor) {
  std::set<std::string> seen;
  sensor->parameters = DefaultSensorParameters(sensor->kind);
  for (const xmlNode* p : xml::Children(node, "parameter")) {
    const std::string name = xml::Attribute(p, "name").value_or("");
    const int index = SensorParameterIndex(sensor->kind, name);
    if (index >= 0) {
      if (!seen.insert(name).second)
        reader.Error(p, what + ": parameter '" + name + "' is given twice");
      else if (const auto value = reader.Number(p, what + " parameter " + name))
        SetTableParameter(reader, p, index, *value, what, sensor);
      continue;
    }
    if (!TakesParameter(sensor->kind, name)) {
      reader.Error(p, what + ": " + ToString(sensor->kind) + " sensors have no parameter '" +
                          name + "'");
      continue;
    }
    if (!seen.insert(name).second) {
      reader.Error(p, what + ": parameter '" + name + "' is given twice");
      continue;
    }
    if (sensor->kind == SensorKind::kCamera)
      SetCameraParameter(reader, p, name, what, &sensor->camera);
    else if (const auto value = reader.Number(p, what + " parameter " + name))
      SetScannerParameter(reader, p, name, *value, what, sensor);
  }
}

// The checks of a new kind across its parameters and rate.
void CheckNewSensor(Reader& reader, const xmlNode* node, const std::string& what,
                    const Sensor& sensor) {
  if (!NeedsRate(sensor.kind)) return;
  if (sensor.rate <= 0.0)
    reader.Error(xml::Child(node, "rate") ? xml::Child(node, "rate") : node,
                 what + ": a " + ToString(sensor.kind) +
                     " sensor samples at its <rate>, which must be above 0 Hz");
  if (sensor.kind != SensorKind::kLidar) return;
  const std::vector<double>& p = sensor.parameters;
  if (p[lidar_param::kMinRange] >= p[lidar_param::kRange])
    reader.Error(node, what + ": minRange " + FormatNumber(p[lidar_param::kMinRange], 10) +
                           " m is not below range " + FormatNumber(p[lidar_param::kRange], 10) +
                           " m");
  if (p[lidar_param::kLowestElevation] > p[lidar_param::kHighestElevation])
    reader.Error(node, what + ": lowestElevation " +
                           FormatNumber(p[lidar_param::kLowestElevation], 10) +
                           " rad is above highestElevation " +
                           FormatNumber(p[lidar_param::kHighestElevation], 10) + " rad");
  const double rays = RaysPerReading(sensor);
  if (rays > kMaxReadingValues)
    reader.Error(node, what + ": rays x layers = " + FormatNumber(rays, 10) +
                           " is more than the " + FormatNumber(kMaxReadingValues, 10) +
                           " values a reading carries (sensor_reading_t)");
  else if (sensor.rate * rays > kMaxScannerRaysPerSecond)
    reader.Error(node, what + ": rate " + FormatNumber(sensor.rate, 10) + " Hz x " +
                           FormatNumber(rays, 10) + " rays (rays x layers) = " +
                           FormatNumber(sensor.rate * rays, 10) + " rays/s is more than the " +
                           FormatNumber(kMaxScannerRaysPerSecond, 10) +
                           " rays/s a scanner may cast (models/.../model.h says why)");
}

std::optional<Sensor> ReadSensor(Reader& reader, const xmlNode* node, const Robot& robot,
                                 const DeclaredNames& declared) {
  Sensor sensor;
  sensor.name = xml::Attribute(node, "name").value_or("");
  sensor.kind = ParseSensorKind(xml::Attribute(node, "type").value_or("Echo"));
  sensor.where = reader.Where(node);
  const std::string what = "sensor '" + sensor.name + "'";
  const size_t errors_before = reader.ErrorCount();
  if (const auto port = ReadPort(reader, node, what)) sensor.port = *port;
  ReadSensorTarget(reader, node, robot, declared, what, &sensor);
  ReadSensorMountAndRate(reader, node, what, &sensor);
  ReadSensorParameters(reader, node, what, &sensor);
  if (reader.ErrorCount() == errors_before) CheckNewSensor(reader, node, what, sensor);
  if (sensor.kind == SensorKind::kScanner && sensor.rate * sensor.rays > kMaxScannerRaysPerSecond)
    reader.Error(node, what + ": rate " + FormatNumber(sensor.rate, 10) + " Hz x " +
                           std::to_string(sensor.rays) + " rays = " +
                           FormatNumber(sensor.rate * sensor.rays, 10) +
                           " rays/s is more than the " + FormatNumber(kMaxScannerRaysPerSecond, 10) +
                           " rays/s a scanner may cast (models/.../model.h says why)");
  if (sensor.kind == SensorKind::kCamera) CheckCamera(reader, node, what, sensor);
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return sensor;
}

// Whether an actuator of this kind can drive a joint of that kind.
bool Drives(ActuatorKind actuator, JointKind joint) {
  const bool rotational = joint == JointKind::kHinge || joint == JointKind::kUniversal ||
                          joint == JointKind::kHinge2;
  switch (actuator) {
    case ActuatorKind::kLinearMotor: return joint == JointKind::kSlider;
    case ActuatorKind::kAngle: return rotational;
    default: return rotational || joint == JointKind::kSlider;
  }
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
  } else if (!Drives(actuator.kind, joint->kind)) {
    reader.Error(joint_ref, what + ": a " + ToString(actuator.kind) + " cannot drive " +
                                ToString(joint->kind) + " joint '" + actuator.joint + "'");
  }
  if (reader.ErrorCount() != errors_before) return std::nullopt;
  return actuator;
}

// Materials, bodies and the joints between them. Body names come from the
// DTD-validated ID attributes, so a joint that names a body which failed
// its own checks is judged against all names.
void ReadRobotStructure(Reader& reader, const xmlNode* root, const DeclaredNames& declared,
                        Robot* robot) {
  for (const xmlNode* n : xml::Children(root, "material"))
    if (auto m = detail::ReadMaterial(reader, n)) robot->materials.push_back(*m);
  for (const xmlNode* n : xml::Children(root, "body"))
    if (auto b = detail::ReadBody(reader, n, "body")) robot->bodies.push_back(*b);
  const std::string owner = "robot '" + robot->model_name + "'";
  auto body_exists = [&](const std::string& name) { return declared.bodies.count(name) > 0; };
  for (const xmlNode* n : xml::Children(root, "joint"))
    if (auto joint = detail::ReadJoint(reader, n, body_exists, owner))
      robot->joints.push_back(*joint);
}

DeclaredNames NamesDeclared(const xmlNode* root) {
  DeclaredNames declared;
  for (const xmlNode* n : xml::Children(root, "body"))
    declared.bodies.insert(xml::Attribute(n, "name").value_or(""));
  for (const xmlNode* n : xml::Children(root, "joint"))
    declared.joints.insert(xml::Attribute(n, "name").value_or(""));
  return declared;
}

// The robot as a whole: connected, rolling bodies with an axis, mass
// ratios (only when all else is right), unique ports, what its sensors
// send together.
void CheckRobot(Reader& reader, const xmlNode* root, const Robot& robot,
                const DiagnosticList& diagnostics) {
  detail::CheckConnected(reader, root);
  // Bodies of the robot's own materials; a world's material of the same
  // name is checked by the world.
  detail::CheckRollingBodies(reader, robot.bodies, robot.joints, "body",
                             [&](const std::string& name) {
                               for (const Material& m : robot.materials)
                                 if (m.name == name) return &m;
                               return static_cast<const Material*>(nullptr);
                             });
  if (diagnostics.empty()) detail::CheckMassRatios(reader, robot.bodies, robot.joints, true);
  std::map<int, std::string> ports;
  detail::CheckUniquePorts(reader, robot, &ports, nullptr, "");
  for (const std::string& excess : RobotBudgetExcesses(robot)) reader.Error(root, excess);
}

}  // namespace

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
  const DeclaredNames declared = NamesDeclared(root);
  ReadRobotStructure(reader, root, declared, &robot);
  for (const xmlNode* n : xml::Children(root, "sensor"))
    if (auto s = ReadSensor(reader, n, robot, declared)) robot.sensors.push_back(*s);
  for (const xmlNode* n : xml::Children(root, "actuator"))
    if (auto a = ReadActuator(reader, n, robot, declared)) robot.actuators.push_back(*a);
  CheckRobot(reader, root, robot, result.diagnostics);
  if (result.diagnostics.empty()) result.robot = std::move(robot);
  return result;
}

RobotLoadResult LoadRobotFile(const std::string& path, const FileReader& read) {
  std::string xml;
  RobotLoadResult result;
  if (!detail::ReadModelFile(path, read, "robot", &xml, &result.diagnostics)) return result;
  return ParseRobot(xml, path);
}

}  // namespace simpartner::model
