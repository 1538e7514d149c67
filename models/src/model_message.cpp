#include "simpartner/model/model_message.h"

#include <string>

#include "simpartner/actuator_t.hpp"
#include "simpartner/sensor_t.hpp"

namespace simpartner::model {
namespace {

int8_t ToLcm(ActuatorKind kind) {
  switch (kind) {
    case ActuatorKind::kJointVelocity: return actuator_t::KIND_JOINT_VELOCITY;
    case ActuatorKind::kAngle: return actuator_t::KIND_ANGLE;
    case ActuatorKind::kLinearMotor: return actuator_t::KIND_LINEAR_MOTOR;
  }
  return actuator_t::KIND_JOINT_VELOCITY;
}

}  // namespace

std::vector<double> CameraParams(const CameraSettings& camera) {
  const double depth = camera.depth == CameraDepth::kMetres        ? 1
                       : camera.depth == CameraDepth::kMillimetres ? 2
                                                                  : 0;
  return {static_cast<double>(camera.width), static_cast<double>(camera.height), camera.fov,
          camera.near, camera.far, depth};
}

namespace {

body_t BodyMessage(const Body& b, int16_t robot, const Eigen::Isometry3d& placement, int32_t id) {
  body_t body{};
  body.id = id;
  body.name = b.name;
  body.robot = robot;
  body.mass = b.mass;
  const Eigen::Isometry3d pose = placement * b.pose;
  const Eigen::Quaterniond q(pose.linear());
  for (int k = 0; k < 3; ++k) body.initial_position[k] = pose.translation()[k];
  body.initial_orientation[0] = q.w();
  body.initial_orientation[1] = q.x();
  body.initial_orientation[2] = q.y();
  body.initial_orientation[3] = q.z();
  return body;
}

// `body_index` maps a body name of the joint's scope to its index (-1: the
// static world).
template <class BodyIndex>
joint_t JointMessage(const Joint& j, int16_t robot, const Eigen::Isometry3d& placement, int32_t id,
                     const BodyIndex& body_index) {
  joint_t joint{};
  joint.id = id;
  joint.name = j.name;
  joint.robot = robot;
  joint.kind = static_cast<int8_t>(j.kind);
  joint.body1 = body_index(j.body1);
  joint.body2 = body_index(j.body2);
  joint.num_axes = static_cast<int8_t>(AxisCount(j.kind));
  const Eigen::Vector3d anchor = placement * j.anchor;
  for (int k = 0; k < 3; ++k) joint.anchor[k] = anchor[k];
  for (int a = 0; a < 2; ++a) {
    const Eigen::Vector3d axis = placement.linear() * j.axis[a];
    for (int k = 0; k < 3; ++k) joint.axis[a][k] = axis[k];
  }
  return joint;
}

}  // namespace

material_t MaterialMessage(const Material& material) {
  material_t out{};
  out.name = material.name;
  out.mu = material.mu;
  out.mu2 = material.Mu2();
  out.friction_direction = material.friction_direction == FrictionDirection::kRolling
                               ? material_t::FRICTION_ROLLING
                               : material_t::FRICTION_SLIP;
  out.bounce = material.bounce;
  out.bounce_velocity = material.bounce_velocity;
  out.soft_erp = material.soft_erp;
  out.soft_cfm = material.soft_cfm;
  out.stiffness = material.stiffness.value_or(0.0);
  out.damping = material.damping.value_or(0.0);
  out.rolling_friction = material.rolling_friction;
  out.is_soil = material.soil.has_value();
  if (material.soil) {
    const SoilParameters& soil = *material.soil;
    out.soil_name = soil.name;
    out.soil_n = soil.n;
    out.soil_kc = soil.k_c;
    out.soil_kphi = soil.k_phi;
    out.soil_cohesion = soil.cohesion;
    out.soil_friction_angle = soil.friction_angle;
    out.soil_shear_modulus = soil.shear_modulus;
    out.soil_unloading_stiffness = soil.unloading_stiffness;
    out.soil_viscosity = soil.viscosity;
  }
  return out;
}

int8_t ToLcm(SensorKind kind) {
  switch (kind) {
    case SensorKind::kEcho: return sensor_t::KIND_ECHO;
    case SensorKind::kPosition: return sensor_t::KIND_POSITION;
    case SensorKind::kScanner: return sensor_t::KIND_SCANNER;
    case SensorKind::kVelocity: return sensor_t::KIND_VELOCITY;
    case SensorKind::kForceTorque: return sensor_t::KIND_FORCE_TORQUE;
    case SensorKind::kImu: return sensor_t::KIND_IMU;
    case SensorKind::kGnss: return sensor_t::KIND_GNSS;
    case SensorKind::kEncoder: return sensor_t::KIND_ENCODER;
    case SensorKind::kLidar: return sensor_t::KIND_LIDAR;
    case SensorKind::kContact: return sensor_t::KIND_CONTACT;
    case SensorKind::kCamera: return sensor_t::KIND_CAMERA;
  }
  return sensor_t::KIND_ECHO;
}

std::vector<double> SensorParamsMessage(const Sensor& sensor, const World& world) {
  if (sensor.kind == SensorKind::kScanner)
    return {static_cast<double>(sensor.rays), sensor.half_span, sensor.range};
  if (sensor.kind == SensorKind::kCamera) return CameraParams(sensor.camera);
  std::vector<double> params = sensor.parameters;
  if (sensor.kind == SensorKind::kGnss) {
    const GeodeticOrigin origin = world.geodetic_origin.value_or(GeodeticOrigin{});
    params.insert(params.end(), {origin.latitude, origin.longitude, origin.altitude});
  }
  return params;
}

model_t ModelMessageFromWorld(const World& world) {
  model_t m{};
  m.world_file = world.file;
  m.world_name = world.name;
  m.step_size = 0.001;
  m.state_every = 1;
  const Eigen::Vector3d up = world.Up();
  for (int k = 0; k < 3; ++k) {
    m.up[k] = up[k];
    m.gravity[k] = world.gravity[k];
  }
  for (const Material& material : world.materials) m.materials.push_back(MaterialMessage(material));
  m.num_materials = static_cast<int16_t>(m.materials.size());
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  for (const Body& b : world.objects)
    m.bodies.push_back(BodyMessage(b, -1, identity, static_cast<int32_t>(m.bodies.size())));
  auto object_index = [&](const std::string& name) -> int32_t {
    for (size_t k = 0; k < world.objects.size(); ++k)
      if (world.objects[k].name == name) return static_cast<int32_t>(k);
    return -1;
  };
  for (const Joint& j : world.joints)
    m.joints.push_back(
        JointMessage(j, -1, identity, static_cast<int32_t>(m.joints.size()), object_index));

  for (size_t r = 0; r < world.robots.size(); ++r) {
    const RobotInstance& instance = world.robots[r];
    const int16_t robot_index = static_cast<int16_t>(r);
    robot_t robot{};
    robot.name = instance.name;
    robot.model = instance.robot.model_name;
    robot.file = instance.file;
    robot.total_mass = instance.robot.TotalMass();
    m.robots.push_back(robot);
    const int32_t first_body = static_cast<int32_t>(m.bodies.size());
    const int32_t first_joint = static_cast<int32_t>(m.joints.size());
    for (const Body& b : instance.robot.bodies)
      m.bodies.push_back(
          BodyMessage(b, robot_index, instance.placement, static_cast<int32_t>(m.bodies.size())));
    auto body_index = [&](const std::string& name) -> int32_t {
      for (size_t k = 0; k < instance.robot.bodies.size(); ++k)
        if (instance.robot.bodies[k].name == name) return first_body + static_cast<int32_t>(k);
      return -1;
    };
    for (const Joint& j : instance.robot.joints)
      m.joints.push_back(JointMessage(j, robot_index, instance.placement,
                                      static_cast<int32_t>(m.joints.size()), body_index));
    auto joint_index = [&](const std::string& name) -> int32_t {
      for (size_t k = 0; k < instance.robot.joints.size(); ++k)
        if (instance.robot.joints[k].name == name) return first_joint + static_cast<int32_t>(k);
      return -1;
    };
    for (const Actuator& a : instance.robot.actuators) {
      actuator_t actuator{};
      actuator.id = static_cast<int32_t>(m.actuators.size());
      actuator.name = a.name;
      actuator.robot = robot_index;
      actuator.kind = ToLcm(a.kind);
      actuator.joint = joint_index(a.joint);
      actuator.port = a.port;
      const Joint* joint = instance.robot.FindJoint(a.joint);
      actuator.num_axes = static_cast<int8_t>(joint ? AxisCount(joint->kind) : 0);
      // The original's slot (x, y, z) of each axis: the one it is most
      // aligned with in the world frame.
      for (int axis = 0; axis < 2 && joint; ++axis) {
        const Eigen::Vector3d direction = instance.placement.linear() * joint->axis[axis];
        Eigen::Index slot = 0;
        direction.cwiseAbs().maxCoeff(&slot);
        actuator.axis_slot[axis] = static_cast<int8_t>(slot);
      }
      m.actuators.push_back(actuator);
    }
    for (const Sensor& s : instance.robot.sensors) {
      sensor_t sensor{};
      sensor.id = static_cast<int32_t>(m.sensors.size());
      sensor.name = s.name;
      sensor.robot = robot_index;
      sensor.kind = ToLcm(s.kind);
      sensor.body = s.body.empty() ? -1 : body_index(s.body);
      sensor.joint = s.joint.empty() ? -1 : joint_index(s.joint);
      sensor.port = s.port;
      const Eigen::Quaterniond mount(s.mount.linear());
      for (int k = 0; k < 3; ++k) sensor.position[k] = s.mount.translation()[k];
      sensor.orientation[0] = mount.w();
      sensor.orientation[1] = mount.x();
      sensor.orientation[2] = mount.y();
      sensor.orientation[3] = mount.z();
      sensor.rate = s.rate;
      sensor.params = SensorParamsMessage(s, world);
      sensor.num_params = static_cast<int32_t>(sensor.params.size());
      m.sensors.push_back(sensor);
    }
  }
  m.num_robots = static_cast<int16_t>(m.robots.size());
  m.num_bodies = static_cast<int32_t>(m.bodies.size());
  m.num_joints = static_cast<int32_t>(m.joints.size());
  m.num_sensors = static_cast<int32_t>(m.sensors.size());
  m.num_actuators = static_cast<int32_t>(m.actuators.size());
  return m;
}

}  // namespace simpartner::model
