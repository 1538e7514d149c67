#include "simpartner/sim/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "simpartner/check.h"
#include "simpartner/model/model_message.h"
#include "simpartner/model/sensor_budget.h"
#include "simpartner/model/sensor_parameters.h"
#include "simpartner/sensor_t.hpp"
#include "simpartner/text.h"
#include "simpartner/sender.h"

namespace simpartner::sim {
namespace {

void Copy3(const Eigen::Vector3d& v, double* out) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

void CopyQuat(const Eigen::Quaterniond& q, double* out) {
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}

int8_t ToLcm(model::GeometryKind kind) {
  switch (kind) {
    case model::GeometryKind::kNone: return geometry_t::KIND_NONE;
    case model::GeometryKind::kBox: return geometry_t::KIND_BOX;
    case model::GeometryKind::kSphere: return geometry_t::KIND_SPHERE;
    case model::GeometryKind::kCylinder: return geometry_t::KIND_CYLINDER;
    case model::GeometryKind::kCapsule: return geometry_t::KIND_CAPSULE;
  }
  return geometry_t::KIND_NONE;
}

int8_t ToLcm(model::JointKind kind) {
  switch (kind) {
    case model::JointKind::kFixed: return joint_t::KIND_FIXED;
    case model::JointKind::kHinge: return joint_t::KIND_HINGE;
    case model::JointKind::kSlider: return joint_t::KIND_SLIDER;
    case model::JointKind::kBall: return joint_t::KIND_BALL;
    case model::JointKind::kUniversal: return joint_t::KIND_UNIVERSAL;
    case model::JointKind::kHinge2: return joint_t::KIND_HINGE2;
  }
  return joint_t::KIND_FIXED;
}

int8_t ToLcm(model::ActuatorKind kind) {
  switch (kind) {
    case model::ActuatorKind::kJointVelocity: return actuator_t::KIND_JOINT_VELOCITY;
    case model::ActuatorKind::kAngle: return actuator_t::KIND_ANGLE;
    case model::ActuatorKind::kLinearMotor: return actuator_t::KIND_LINEAR_MOTOR;
  }
  return actuator_t::KIND_JOINT_VELOCITY;
}

constexpr size_t kMaxWarnings = 64;

}  // namespace

Simulation::Simulation(model::World world, Parameters params, int64_t simulation_id)
    : world_(std::move(world)),
      params_(std::move(params)),
      simulation_id_(simulation_id),
      noise_(static_cast<uint64_t>(params_.sensorSeed)) {
  flat_ = model::Flatten(world_);
  ruts_ = SoilRuts(world_);
  Build();
}

void Simulation::Build() {
  engine_.reset();
  bodies_read_ = false;
  ruts_.Clear();
  engine_ = MakeEngine(flat_, params_);
  controllers_.clear();
  for (const model::FlatActuator& a : flat_.actuators) {
    const model::FlatJoint& joint = flat_.joints[static_cast<size_t>(a.joint)];
    controllers_.emplace_back(joint.num_axes, joint.source->kind != model::JointKind::kSlider);
  }
  sensors_.clear();
  for (const model::FlatSensor& s : flat_.sensors) {
    SensorState state;
    state.rate = s.source->rate;
    state.rays = s.source->rays;
    state.half_span = s.source->half_span;
    state.range = s.source->range;
    // A camera's rate is simpartner-camera's to keep: the sim reads nothing.
    const bool read_here = state.rate > 0 && s.source->kind != model::SensorKind::kCamera;
    state.period_steps =
        read_here ? std::max<int64_t>(1, std::llround(1.0 / (state.rate * params_.stepsize))) : 0;
    state.imu = s.source->kind == model::SensorKind::kImu;
    sensors_.push_back(state);
  }
  pending_.Clear();
  step_ = 0;
  faulted_ = false;
  SettleOnSoil();
  RememberImuVelocities();
}

// An IMU's acceleration is the change of its mount point's velocity over
// a step: remember the velocity before each step.
void Simulation::RememberImuVelocities() {
  for (size_t s = 0; s < sensors_.size(); ++s) {
    if (!sensors_[s].imu) continue;
    const model::FlatSensor& sensor = flat_.sensors[s];
    const BodyReadout body = engine_->ReadBody(sensor.body);
    const Eigen::Vector3d point =
        body.position + body.orientation * sensor.source->mount.translation();
    sensors_[s].imu_memory.previous_velocity = PointVelocity(body, point);
  }
}

void Simulation::WalkImuBiases() {
  for (size_t s = 0; s < sensors_.size(); ++s) {
    if (sensors_[s].imu)
      WalkImuBias(*flat_.sensors[s].source, noise_, static_cast<int>(s), step_, params_.stepsize,
                  &sensors_[s].imu_memory);
  }
}

void Simulation::Reset(int64_t simulation_id) {
  simulation_id_ = simulation_id;
  Build();
  AddWarning(warning_t::SEVERITY_INFO, "control", "reset to the initial state");
}

command_reply_t Simulation::Reply(const command_t& command, bool accepted,
                                  const std::string& reason) const {
  command_reply_t reply{};
  reply.utime = WallMicros();
  reply.simulation_id = simulation_id_;
  reply.request_id = command.request_id;
  reply.sender = command.sender;
  reply.target = command.target;
  reply.accepted = accepted;
  reply.reason = reason;
  reply.applied_at_step = -1;
  reply.num_previous = 0;
  return reply;
}

std::optional<command_reply_t> Simulation::Submit(const command_t& command) {
  auto reject = [&](const std::string& reason) { return Reply(command, false, reason); };
  // Two systems on one bus must not steer each other: a command names the
  // simulation it was built for (0 = whichever sim hears it).
  if (command.simulation_id != 0 && command.simulation_id != simulation_id_)
    return reject("simulation_id = " + std::to_string(command.simulation_id) +
                  ": the command is meant for another simulation (this one is " +
                  std::to_string(simulation_id_) + ")");
  if (command.num_values < 0 || static_cast<size_t>(command.num_values) != command.values.size())
    return reject("num_values = " + std::to_string(command.num_values) + " does not match " +
                  std::to_string(command.values.size()) + " values");
  PendingCommand pending;
  pending.command = command;
  // Find the target: by name (optionally within a robot) or legacy port.
  const bool by_name = !command.target.empty();
  if (by_name && command.port != 0)
    return reject("both target '" + command.target + "' and port " +
                  std::to_string(command.port) + " are given; use one");
  if (!command.robot.empty()) {
    bool known = false;
    for (const model::RobotInstance& r : world_.robots) known |= r.name == command.robot;
    if (!known) return reject("robot '" + command.robot + "' does not exist");
  }
  if (by_name) {
    pending.actuator = flat_.FindActuator(command.robot, command.target);
    if (pending.actuator < 0) pending.sensor = flat_.FindSensor(command.robot, command.target);
    if (pending.actuator < 0 && pending.sensor < 0)
      return reject("target '" + command.target + "' is not an actuator or sensor" +
                    (command.robot.empty() ? std::string() : " of robot '" + command.robot + "'"));
  } else {
    if (command.port <= 1024 || command.port > 65535)
      return reject("port " + std::to_string(command.port) +
                    " is out of range (legacy ports are 1025 to 65535)");
    pending.actuator = flat_.FindActuatorByPort(command.port);
    if (pending.actuator < 0) pending.sensor = flat_.FindSensorByPort(command.port);
    if (pending.actuator < 0 && pending.sensor < 0)
      return reject("port " + std::to_string(command.port) + " is not an actuator or sensor");
  }
  if (command.apply_at_step < -1)
    return reject("apply_at_step = " + std::to_string(command.apply_at_step) +
                  " (use -1 for 'as soon as received')");
  if (command.apply_at_step >= 0 && command.apply_at_step < step_)
    return reject("apply_at_step = " + std::to_string(command.apply_at_step) +
                  " has passed (the sim is at step " + std::to_string(step_) + ")");
  pending.step = command.apply_at_step >= 0 ? command.apply_at_step : step_;

  // Numbers come from values[] or, when it is empty, the original's text
  // form; an echo sensor's text is not numbers.
  std::vector<double> values;
  std::string error;
  const bool echo_text = pending.sensor >= 0 && command.action != command_t::ACTION_SENSOR_PARAMS;
  if (!echo_text && !CommandValues(command.values, command.text, &values, &error))
    return reject(error);

  if (pending.actuator >= 0) {
    const model::FlatActuator& actuator = flat_.actuators[static_cast<size_t>(pending.actuator)];
    pending.command.target = actuator.name;
    const model::FlatJoint& joint = flat_.joints[static_cast<size_t>(actuator.joint)];
    pending.parsed = ParseActuatorCommand(command.action, values, actuator.source->kind, joint,
                                          controllers_[static_cast<size_t>(pending.actuator)].setting());
    if (!pending.parsed.error.empty())
      return reject("actuator '" + actuator.name + "' (" + ToString(actuator.source->kind) +
                    "): " + pending.parsed.error);
  } else {
    const model::FlatSensor& sensor = flat_.sensors[static_cast<size_t>(pending.sensor)];
    pending.command.target = sensor.name;
    const std::string what = "sensor '" + sensor.name + "' (" + ToString(sensor.source->kind) + ")";
    if (sensor.source->kind == model::SensorKind::kCamera)
      return reject(what + ": simpartner-camera renders it (image_t on SIM_IMAGE); the sim "
                           "takes no command for a camera");
    switch (command.action) {
      case command_t::ACTION_READ:
        break;
      case command_t::ACTION_SET:
        if (sensor.source->kind != model::SensorKind::kEcho)
          return reject(what + ": only an Echo sensor takes a SET; use SENSOR_PARAMS");
        break;
      case command_t::ACTION_SENSOR_PARAMS: {
        const bool scanner = sensor.source->kind == model::SensorKind::kScanner;
        const bool lidar = sensor.source->kind == model::SensorKind::kLidar;
        if (values.size() != 1 && !(scanner && values.size() == 4))
          return reject(what + ": expected 1 value (rate)" +
                        std::string(scanner ? " or 4 (rate, rays, halfSpan, range)" : "") +
                        ", got " + std::to_string(values.size()));
        for (size_t k = 0; k < values.size(); ++k) {
          if (!std::isfinite(values[k]))
            return reject(what + ": values[" + std::to_string(k) + "] = " + FormatNumber(values[k], 10) +
                          " is not a finite number");
        }
        if (values[0] < 0 || values[0] > 10000)
          return reject(what + ": values[0] (rate) = " + FormatNumber(values[0], 10) +
                        " Hz is out of range [0, 10000]");
        if (lidar) {
          const double rays = model::RaysPerReading(*sensor.source);
          if (values[0] * rays > model::kMaxScannerRaysPerSecond)
            return reject(what + ": rate " + FormatNumber(values[0], 10) + " Hz x " +
                          FormatNumber(rays, 10) + " rays = " + FormatNumber(values[0] * rays, 10) +
                          " rays/s is more than the " +
                          FormatNumber(model::kMaxScannerRaysPerSecond, 10) +
                          " rays/s a scanner may cast (the bus carries a double per ray)");
        }
        if (values.size() == 4) {
          if (values[1] < 1 || values[1] > 10000 || values[1] != std::floor(values[1]))
            return reject(what + ": values[1] (rays) = " + FormatNumber(values[1], 10) +
                          " must be a whole number from 1 to 10000");
          if (values[2] < 0 || values[2] > M_PI)
            return reject(what + ": values[2] (halfSpan) = " + FormatNumber(values[2], 10) +
                          " rad is out of range [0, pi]");
          if (values[3] <= 0 || values[3] > 1e4)
            return reject(what + ": values[3] (range) = " + FormatNumber(values[3], 10) +
                          " m is out of range (0, 10000]");
        }
        // Without rays in the command: the scanner's present number.
        const size_t index = static_cast<size_t>(pending.sensor);
        const double rays = values.size() == 4 ? values[1] : sensors_[index].rays;
        if (scanner && values[0] * rays > model::kMaxScannerRaysPerSecond)
          return reject(what + ": rate " + FormatNumber(values[0], 10) + " Hz x " +
                        FormatNumber(rays, 10) + " rays = " + FormatNumber(values[0] * rays, 10) +
                        " rays/s is more than the " +
                        FormatNumber(model::kMaxScannerRaysPerSecond, 10) +
                        " rays/s a scanner may cast (the bus carries a double per ray)");
        break;
      }
      default:
        return reject(what + ": action " + std::to_string(command.action) +
                      " does not apply to a sensor");
    }
    pending.values = values;
  }
  // Bounded and shared fairly among senders (command_queue.h).
  std::vector<DroppedCommand> dropped;
  const std::string full = pending_.Add(std::move(pending), step_, &dropped);
  for (const DroppedCommand& d : dropped) replies_.push_back(Reply(d.command, false, d.reason));
  if (!full.empty()) return reject(full);
  return std::nullopt;
}

void Simulation::ApplyPending(const PendingCommand& pending) {
  command_reply_t reply = Reply(pending.command, true, "");
  reply.target = pending.command.target;
  reply.applied_at_step = step_;
  if (pending.actuator >= 0) {
    const size_t index = static_cast<size_t>(pending.actuator);
    const model::FlatActuator& actuator = flat_.actuators[index];
    const model::FlatJoint& joint = flat_.joints[static_cast<size_t>(actuator.joint)];
    ActuatorController& controller = controllers_[index];
    const std::vector<double> previous = SettingToSlotValues(controller.setting(), joint);
    reply.previous = previous;
    if (pending.parsed.sets_stops) {
      for (int a = 0; a < joint.num_axes; ++a)
        engine_->SetStops(actuator.joint, a, pending.parsed.lo[a], pending.parsed.hi[a]);
    } else {
      ActuatorSetting setting = pending.parsed.setting;
      if (setting.mode == ControlMode::kHold) {
        for (int a = 0; a < joint.num_axes; ++a)
          setting.target[a] = engine_->JointPosition(actuator.joint, a);
      }
      controller.Apply(setting);
    }
    reply.num_previous = static_cast<int32_t>(reply.previous.size());
    reply.previous_text = FormatValues(reply.previous);
  } else {
    SensorState& sensor = sensors_[static_cast<size_t>(pending.sensor)];
    switch (pending.command.action) {
      case command_t::ACTION_SET:
        reply.previous_text = sensor.echo_text;
        sensor.echo_text = pending.command.text;
        read_requests_.push_back(pending.sensor);
        break;
      case command_t::ACTION_READ:
        read_requests_.push_back(pending.sensor);
        break;
      case command_t::ACTION_SENSOR_PARAMS: {
        const SensorState before = sensor;
        reply.previous = {sensor.rate};
        if (flat_.sensors[static_cast<size_t>(pending.sensor)].source->kind ==
            model::SensorKind::kScanner) {
          reply.previous.insert(reply.previous.end(),
                                {static_cast<double>(sensor.rays), sensor.half_span, sensor.range});
        }
        sensor.rate = pending.values[0];
        sensor.period_steps =
            sensor.rate > 0
                ? std::max<int64_t>(1, std::llround(1.0 / (sensor.rate * params_.stepsize)))
                : 0;
        if (pending.values.size() == 4) {
          sensor.rays = static_cast<int>(pending.values[1]);
          sensor.half_span = pending.values[2];
          sensor.range = pending.values[3];
        }
        // The robot's other sensors may have changed since the command
        // came: its budget is checked as it applies.
        const std::string excess =
            RobotRaysExcess(flat_.sensors[static_cast<size_t>(pending.sensor)].robot);
        if (!excess.empty()) {
          sensor = before;
          replies_.push_back(Reply(pending.command, false, excess));
          return;
        }
        reply.num_previous = static_cast<int32_t>(reply.previous.size());
        reply.previous_text = FormatValues(reply.previous);
        break;
      }
      default:
        break;
    }
  }
  replies_.push_back(std::move(reply));
}

std::string Simulation::RobotRaysExcess(int robot) const {
  std::vector<model::SensorLoad> loads;
  for (size_t s = 0; s < sensors_.size(); ++s) {
    const model::FlatSensor& flat = flat_.sensors[s];
    if (flat.robot != robot || model::RaysPerReading(*flat.source) == 0.0) continue;
    const double rays = flat.source->kind == model::SensorKind::kScanner
                            ? sensors_[s].rays
                            : model::RaysPerReading(*flat.source);
    loads.push_back({flat.name, sensors_[s].rate * rays});
  }
  return model::BudgetExcess(world_.robots[static_cast<size_t>(robot)].name, loads,
                             model::kMaxRobotRaysPerSecond, "scanners and lidars", "rays/s");
}

bool Simulation::Step() {
  if (faulted_) return false;
  bodies_read_ = false;
  // Commands due in this step, in the order they were sent.
  pending_.TakeDue(step_, [this](const PendingCommand& p) { ApplyPending(p); });
  UpdateControllers();
  RememberImuVelocities();
  if (!StepEngine("; the sim is paused: reset to go on")) return false;
  ++step_;
  WalkImuBiases();
  SayEngineMessages();
  ReadBodies();
  CheckHealth();
  if (faulted_) return false;
  ruts_.Stamp(wheel_soil_);

  for (size_t s = 0; s < sensors_.size(); ++s) {
    const SensorState& sensor = sensors_[s];
    if (sensor.period_steps > 0 && step_ % sensor.period_steps == 0)
      readings_.push_back(ReadSensor(static_cast<int>(s)));
  }
  for (int s : read_requests_) readings_.push_back(ReadSensor(s));
  read_requests_.clear();
  if (readings_.size() > kMaxUntakenReadings)
    readings_.erase(readings_.begin(),
                    readings_.end() - static_cast<std::ptrdiff_t>(kMaxUntakenReadings / 2));
  return true;
}

bool Simulation::StepEngine(const std::string& then) {
  try {
    engine_->Step();
    return true;
  } catch (const EngineError& e) {
    // The engine gave up inside the step (its state is lost): pause as for
    // an exploding state, naming its message and the bodies; a reset builds
    // a new world.
    faulted_ = true;
    AddWarning(warning_t::SEVERITY_ERROR, engine_->name(), std::string(e.what()) + then,
               e.bodies());
    return false;
  }
}

void Simulation::SayEngineMessages() {
  for (const std::string& message : engine_->last_messages())
    AddWarning(warning_t::SEVERITY_WARNING, engine_->name(), message);
}

void Simulation::UpdateControllers() {
  for (size_t a = 0; a < controllers_.size(); ++a) {
    const int joint = flat_.actuators[a].joint;
    const int axes = flat_.joints[static_cast<size_t>(joint)].num_axes;
    double position[2] = {0, 0}, rate[2] = {0, 0};
    for (int k = 0; k < axes; ++k) {
      position[k] = engine_->JointPosition(joint, k);
      rate[k] = engine_->JointRate(joint, k);
    }
    const MotorOutput out = controllers_[a].Update(position, rate, params_.stepsize);
    for (int k = 0; k < axes; ++k) engine_->SetMotor(joint, k, out.velocity[k], out.max_force[k]);
  }
}

void Simulation::ReadBodies() {
  bodies_.resize(flat_.bodies.size());
  for (size_t i = 0; i < flat_.bodies.size(); ++i)
    bodies_[i] = engine_->ReadBody(static_cast<int>(i));
  wheel_soil_ = engine_->ReadWheelSoil();
  bodies_read_ = true;
}

void Simulation::CheckHealth() {
  std::vector<std::string> bad;
  std::string worst;
  for (size_t i = 0; i < flat_.bodies.size(); ++i) {
    if (flat_.bodies[i].source->is_static) continue;
    const BodyReadout& b = bodies_[i];
    const bool finite = b.position.allFinite() && b.orientation.coeffs().allFinite() &&
                        b.linear_velocity.allFinite() && b.angular_velocity.allFinite();
    const double v = b.linear_velocity.norm();
    const double w = b.angular_velocity.norm();
    if (!finite || v > params_.maxLinearVelocity || w > params_.maxAngularVelocity) {
      bad.push_back(model::QualifiedBodyName(flat_, static_cast<int>(i)));
      if (worst.empty()) {
        worst = !finite ? "non-finite state"
                        : "speed " + FormatNumber(v, 10) + " m/s, rotation " + FormatNumber(w, 10) +
                              " rad/s beyond maxLinearVelocity " + FormatNumber(params_.maxLinearVelocity, 10) +
                              " / maxAngularVelocity " + FormatNumber(params_.maxAngularVelocity, 10);
      }
    }
  }
  if (bad.empty()) return;
  faulted_ = true;
  std::string names;
  for (const std::string& n : bad) names += (names.empty() ? "" : ", ") + n;
  AddWarning(warning_t::SEVERITY_ERROR, "health",
             "simulation exploded at step " + std::to_string(step_) + " (" + worst +
                 "); bodies: " + names + ". Paused; reset to continue",
             bad);
}

void Simulation::AddWarning(int8_t severity, const std::string& source,
                            const std::string& message, std::vector<std::string> bodies) {
  warning_t w{};
  w.step = step_;
  w.severity = severity;
  w.source = source;
  w.message = message;
  w.num_bodies = static_cast<int16_t>(bodies.size());
  w.bodies = std::move(bodies);
  if (warnings_.size() >= kMaxWarnings) warnings_.erase(warnings_.begin());
  warnings_.push_back(std::move(w));
}

std::vector<command_reply_t> Simulation::TakeReplies() { return std::exchange(replies_, {}); }
std::vector<sensor_reading_t> Simulation::TakeSensorReadings() {
  return std::exchange(readings_, {});
}
std::vector<warning_t> Simulation::TakeWarnings() { return std::exchange(warnings_, {}); }

sensor_reading_t Simulation::ReadSensor(int index) {
  const model::FlatSensor& sensor = flat_.sensors[static_cast<size_t>(index)];
  const SensorState& state = sensors_[static_cast<size_t>(index)];
  sensor_reading_t r{};
  r.utime = WallMicros();
  r.simulation_id = simulation_id_;
  r.step = step_;
  r.sim_time = time();
  r.sensor = index;
  r.name = sensor.name;
  r.kind = model::ToLcm(sensor.source->kind);
  if (sensor.source->kind == model::SensorKind::kEcho) r.text = state.echo_text;
  r.values = ReadValues(SensorInputOf(index), state);
  r.num_values = static_cast<int32_t>(r.values.size());
  return r;
}

SensorInput Simulation::SensorInputOf(int index) {
  const model::FlatSensor& sensor = flat_.sensors[static_cast<size_t>(index)];
  const SensorState& state = sensors_[static_cast<size_t>(index)];
  SensorInput in;
  in.engine = engine_.get();
  in.sensor = &sensor;
  in.world = &world_;
  in.noise = &noise_;
  in.index = index;
  in.step = step_;
  // Its noise is that of sampling at its rate; with publishing off (rate
  // 0, on request only), at the rate its file gives.
  in.rate = state.rate > 0 ? state.rate : sensor.source->rate;
  if (sensor.body >= 0) {
    in.body = engine_->ReadBody(sensor.body);
    Eigen::Isometry3d body_pose = Eigen::Isometry3d::Identity();
    body_pose.linear() = in.body.orientation.toRotationMatrix();
    body_pose.translation() = in.body.position;
    in.mount = body_pose * sensor.source->mount;
  }
  return in;
}

std::vector<double> Simulation::ReadValues(const SensorInput& in, const SensorState& state) {
  switch (in.sensor->source->kind) {
    case model::SensorKind::kEcho: return {};  // its text
    case model::SensorKind::kCamera: return {};  // never asked: simpartner-camera renders it
    case model::SensorKind::kPosition: return ReadPosition(in);
    case model::SensorKind::kVelocity: return ReadVelocity(in);
    case model::SensorKind::kForceTorque: return ReadForceTorque(in);
    case model::SensorKind::kScanner:
      return ReadScanner(in, ScannerSettings{state.rays, state.half_span, state.range});
    case model::SensorKind::kImu: return ReadImu(in, state.imu_memory, params_.stepsize);
    case model::SensorKind::kGnss: return ReadGnss(in);
    case model::SensorKind::kEncoder: return ReadEncoder(in);
    case model::SensorKind::kLidar: return ReadLidar(in);
    case model::SensorKind::kContact: return ReadContact(in);
  }
  return {};
}

void Simulation::FillState(state_t* s) const {
  s->utime = WallMicros();
  s->simulation_id = simulation_id_;
  s->step = step_;
  s->sim_time = time();
  s->num_bodies = static_cast<int32_t>(flat_.bodies.size());
  s->bodies.resize(flat_.bodies.size());
  for (size_t i = 0; i < flat_.bodies.size(); ++i) {
    const BodyReadout b = bodies_read_ ? bodies_[i] : engine_->ReadBody(static_cast<int>(i));
    body_state_t& out = s->bodies[i];
    Copy3(b.position, out.position);
    CopyQuat(b.orientation, out.orientation);
    Copy3(b.linear_velocity, out.linear_velocity);
    Copy3(b.angular_velocity, out.angular_velocity);
    Copy3(b.contact_force, out.contact_force);
    Copy3(b.contact_torque, out.contact_torque);
  }
  s->num_joints = static_cast<int32_t>(flat_.joints.size());
  s->joints.resize(flat_.joints.size());
  for (size_t j = 0; j < flat_.joints.size(); ++j) {
    const JointReadout r = engine_->ReadJoint(static_cast<int>(j));
    joint_state_t& out = s->joints[j];
    for (int a = 0; a < 3; ++a) {
      out.position[a] = r.position[a];
      out.continuous_position[a] = r.continuous_position[a];
      out.rate[a] = r.rate[a];
    }
    Copy3(r.anchor, out.anchor);
    Copy3(r.force1, out.force1);
    Copy3(r.torque1, out.torque1);
    Copy3(r.force2, out.force2);
    Copy3(r.torque2, out.torque2);
  }
  FillWheelSoil(s);
}

void Simulation::FillWheelSoil(state_t* s) const {
  const std::vector<WheelSoilReadout> read =
      bodies_read_ ? std::vector<WheelSoilReadout>{} : engine_->ReadWheelSoil();
  const std::vector<WheelSoilReadout>& wheels = bodies_read_ ? wheel_soil_ : read;
  s->num_wheel_soil = static_cast<int32_t>(wheels.size());
  s->wheel_soil.resize(wheels.size());
  for (size_t w = 0; w < wheels.size(); ++w) {
    const WheelSoilReadout& in = wheels[w];
    wheel_soil_t& out = s->wheel_soil[w];
    out.body = in.body;
    out.sinkage = in.sinkage;
    out.slip = in.slip;
    Copy3(in.normal_force, out.normal_force);
    Copy3(in.shear_force, out.shear_force);
    const Eigen::Vector3d force = in.normal_force + in.shear_force;
    out.thrust = in.shear_force.dot(in.forward);
    out.drawbar_pull = force.dot(in.forward);
    out.load = force.dot(in.up);
    out.axle_torque = in.axle_torque;
    out.stuck = in.stuck;
  }
}

void Simulation::FillModel(model_t* m) const {
  *m = model_t{};
  m->utime = WallMicros();
  m->simulation_id = simulation_id_;
  m->engine = params_.engine;
  m->world_file = world_.file;
  m->world_name = world_.name;
  m->parameters = FormatParameters(params_);
  m->step_size = params_.stepsize;
  m->state_every = params_.stateEvery;
  Copy3(world_.gravity, m->gravity);
  Copy3(world_.Up(), m->up);
  m->has_plane = world_.has_plane;
  for (int k = 0; k < 4; ++k) m->plane[k] = world_.plane[k];
  m->plane_material = world_.plane_material;
  if (world_.heightfield) {
    const model::Heightfield& h = *world_.heightfield;
    heightfield_t& out = m->heightfield;
    out.present = true;
    out.rows = h.rows;
    out.columns = h.columns;
    out.width = h.width;
    out.depth = h.depth;
    out.scale = h.scale;
    out.offset = h.offset;
    out.thickness = h.thickness;
    Copy3(h.position, out.position);
    out.material = h.material;
    out.samples.assign(h.samples.begin(), h.samples.end());
    out.num_samples = static_cast<int32_t>(out.samples.size());
  }
  for (const model::Material& mat : world_.materials) m->materials.push_back(model::MaterialMessage(mat));
  m->num_materials = static_cast<int16_t>(m->materials.size());
  for (const model::RobotInstance& r : world_.robots) {
    robot_t robot{};
    robot.name = r.name;
    robot.model = r.robot.model_name;
    robot.file = r.file;
    robot.total_mass = r.robot.TotalMass();
    m->robots.push_back(robot);
  }
  m->num_robots = static_cast<int16_t>(m->robots.size());
  for (size_t i = 0; i < flat_.bodies.size(); ++i) {
    const model::FlatBody& fb = flat_.bodies[i];
    const model::Body& src = *fb.source;
    body_t b{};
    b.id = static_cast<int32_t>(i);
    b.name = fb.name;
    b.robot = static_cast<int16_t>(fb.robot);
    b.geometry.kind = ToLcm(src.geometry.kind);
    Copy3(src.geometry.size, b.geometry.size);
    b.material = src.material;
    b.mass = src.mass;
    Copy3(src.com, b.com);
    const Eigen::Matrix3d& I = src.inertia;
    b.inertia[0] = I(0, 0);
    b.inertia[1] = I(1, 1);
    b.inertia[2] = I(2, 2);
    b.inertia[3] = I(0, 1);
    b.inertia[4] = I(0, 2);
    b.inertia[5] = I(1, 2);
    Copy3(fb.pose.translation(), b.initial_position);
    CopyQuat(Eigen::Quaterniond(fb.pose.linear()), b.initial_orientation);
    b.is_static = src.is_static;
    m->bodies.push_back(b);
  }
  m->num_bodies = static_cast<int32_t>(m->bodies.size());
  for (size_t j = 0; j < flat_.joints.size(); ++j) {
    const model::FlatJoint& fj = flat_.joints[j];
    joint_t out{};
    out.id = static_cast<int32_t>(j);
    out.name = fj.name;
    out.robot = static_cast<int16_t>(fj.robot);
    out.kind = ToLcm(fj.source->kind);
    out.body1 = fj.body1;
    out.body2 = fj.body2;
    out.num_axes = static_cast<int8_t>(fj.num_axes);
    Copy3(fj.anchor, out.anchor);
    for (int a = 0; a < 3; ++a) {
      for (int k = 0; k < 3; ++k) out.axis[a][k] = 0.0;
      out.lo_stop[a] = fj.source->lo_stop[a];
      out.hi_stop[a] = fj.source->hi_stop[a];
    }
    for (int a = 0; a < fj.num_axes; ++a) Copy3(fj.axis[a], out.axis[a]);
    m->joints.push_back(out);
  }
  m->num_joints = static_cast<int32_t>(m->joints.size());
  for (size_t s = 0; s < flat_.sensors.size(); ++s) {
    const model::FlatSensor& fs = flat_.sensors[s];
    const SensorState& state = sensors_[s];
    sensor_t out{};
    out.id = static_cast<int32_t>(s);
    out.name = fs.name;
    out.robot = static_cast<int16_t>(fs.robot);
    out.kind = model::ToLcm(fs.source->kind);
    out.body = fs.body;
    out.joint = fs.joint;
    out.port = fs.source->port;
    Copy3(fs.source->mount.translation(), out.position);
    CopyQuat(Eigen::Quaterniond(fs.source->mount.linear()), out.orientation);
    out.rate = state.rate;
    if (fs.source->kind == model::SensorKind::kScanner)
      out.params = {static_cast<double>(state.rays), state.half_span, state.range};
    else
      out.params = model::SensorParamsMessage(*fs.source, world_);
    out.num_params = static_cast<int32_t>(out.params.size());
    m->sensors.push_back(out);
  }
  m->num_sensors = static_cast<int32_t>(m->sensors.size());
  for (size_t a = 0; a < flat_.actuators.size(); ++a) {
    const model::FlatActuator& fa = flat_.actuators[a];
    actuator_t out{};
    out.id = static_cast<int32_t>(a);
    out.name = fa.name;
    out.robot = static_cast<int16_t>(fa.robot);
    out.kind = ToLcm(fa.source->kind);
    out.joint = fa.joint;
    out.port = fa.source->port;
    const model::FlatJoint& joint = flat_.joints[static_cast<size_t>(fa.joint)];
    out.num_axes = static_cast<int8_t>(joint.num_axes);
    out.axis_slot[0] = static_cast<int8_t>(joint.slot[0]);
    out.axis_slot[1] = static_cast<int8_t>(joint.slot[1]);
    m->actuators.push_back(out);
  }
  m->num_actuators = static_cast<int32_t>(m->actuators.size());
}

}  // namespace simpartner::sim
