#include "simpartner/sim/sensor_readings.h"

#include <algorithm>
#include <cmath>

#include "simpartner/model/sensor_parameters.h"
#include "simpartner/sim/geodetic.h"

namespace simpartner::sim {
namespace {

namespace ip = model::imu_param;
namespace gp = model::gnss_param;
namespace lp = model::lidar_param;

// Noise components of a reading (the last part of the noise key).
enum ImuComponent { kAccel = 0, kGyro = 3, kAccelWalk = 6, kGyroWalk = 9 };
enum GnssComponent { kPosition = 0, kVelocity = 3 };

double Param(const SensorInput& in, int index) {
  return in.sensor->source->parameters[static_cast<size_t>(index)];
}

// value + sigma x a standard normal of component `component` (none when
// sigma is 0, so that a noise-free sensor reads the exact value).
double Noisy(const SensorInput& in, double value, double sigma, int component) {
  if (sigma == 0.0) return value;
  return value + sigma * in.noise->Gaussian(in.index, in.step, component);
}

}  // namespace

Eigen::Vector3d PointVelocity(const BodyReadout& body, const Eigen::Vector3d& point) {
  return body.linear_velocity + body.angular_velocity.cross(point - body.position);
}

void WalkImuBias(const model::Sensor& sensor, const SensorNoise& noise, int index, int64_t step,
                 double stepsize, ImuMemory* memory) {
  // A random walk of density q grows by q sqrt(dt) per interval dt: per
  // step here, so that the bias does not depend on when it is read.
  const double accel = sensor.parameters[ip::kAccelBiasRandomWalk] * std::sqrt(stepsize);
  const double gyro = sensor.parameters[ip::kGyroBiasRandomWalk] * std::sqrt(stepsize);
  for (int k = 0; k < 3; ++k) {
    if (accel > 0.0) memory->accel_walk[k] += accel * noise.Gaussian(index, step, kAccelWalk + k);
    if (gyro > 0.0) memory->gyro_walk[k] += gyro * noise.Gaussian(index, step, kGyroWalk + k);
  }
}

std::vector<double> ReadPosition(const SensorInput& in) {
  const Eigen::Vector3d p = in.mount.translation();
  const Eigen::Quaterniond q(in.mount.linear());
  return {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()};
}

std::vector<double> ReadVelocity(const SensorInput& in) {
  const Eigen::Vector3d v = PointVelocity(in.body, in.mount.translation());
  const Eigen::Vector3d& w = in.body.angular_velocity;
  return {v.x(), v.y(), v.z(), w.x(), w.y(), w.z()};
}

std::vector<double> ReadForceTorque(const SensorInput& in) {
  const JointReadout j = in.engine->ReadJoint(in.sensor->joint);
  return {j.force2.x(), j.force2.y(), j.force2.z(), j.torque2.x(), j.torque2.y(), j.torque2.z()};
}

std::vector<double> ReadScanner(const SensorInput& in, const ScannerSettings& settings) {
  // Rays around the sensor's z axis in its z-x plane, evenly from
  // -halfSpan to +halfSpan.
  std::vector<double> out(static_cast<size_t>(settings.rays));
  for (int k = 0; k < settings.rays; ++k) {
    const double angle = settings.rays == 1 ? 0.0
                                            : -settings.half_span +
                                                  2.0 * settings.half_span * k / (settings.rays - 1);
    const Eigen::Vector3d direction =
        in.mount.linear() * Eigen::Vector3d(std::sin(angle), 0.0, std::cos(angle));
    out[static_cast<size_t>(k)] =
        in.engine->CastRay(in.mount.translation(), direction, settings.range, in.sensor->body);
  }
  return out;
}

std::vector<double> ReadImu(const SensorInput& in, const ImuMemory& memory, double stepsize) {
  // Acceleration of the mount point as the integrator made it: the change
  // of its velocity over the last step (lever-arm terms included, as the
  // point's velocity has them). An accelerometer feels a - g.
  const Eigen::Vector3d point = in.mount.translation();
  const Eigen::Vector3d velocity = PointVelocity(in.body, point);
  const Eigen::Vector3d acceleration = (velocity - memory.previous_velocity) / stepsize;
  const Eigen::Matrix3d to_sensor = in.mount.linear().transpose();
  const Eigen::Vector3d specific_force = to_sensor * (acceleration - in.world->gravity);
  const Eigen::Vector3d rate = to_sensor * in.body.angular_velocity;
  // White noise of density d sampled at f Hz has standard deviation d sqrt(f).
  const double accel_sigma = Param(in, ip::kAccelNoiseDensity) * std::sqrt(in.rate);
  const double gyro_sigma = Param(in, ip::kGyroNoiseDensity) * std::sqrt(in.rate);
  const Eigen::Quaterniond q(in.mount.linear());
  std::vector<double> values(10);
  for (int k = 0; k < 3; ++k) {
    const size_t i = static_cast<size_t>(k);
    values[i] = Noisy(in, specific_force[k] + Param(in, ip::kAccelBiasX + k) + memory.accel_walk[k],
                      accel_sigma, kAccel + k);
    values[3 + i] = Noisy(in, rate[k] + Param(in, ip::kGyroBiasX + k) + memory.gyro_walk[k],
                          gyro_sigma, kGyro + k);
  }
  values[6] = q.w();
  values[7] = q.x();
  values[8] = q.y();
  values[9] = q.z();
  return values;
}

std::vector<double> ReadGnss(const SensorInput& in) {
  const Eigen::Vector3d point = in.mount.translation();
  const LocalFrame frame = LocalFrameOf(in.world->Up());
  const double cover = Param(in, gp::kCoverHeight);
  if (cover > 0.0 &&
      in.engine->CastRay(point, frame.up, cover, in.sensor->body) < cover) {
    // Geometry above the antenna within coverHeight: no fix, and zeros
    // (finite: every reader on the bus refuses non-finite values).
    return std::vector<double>(10, 0.0);
  }
  const Eigen::Vector3d v = PointVelocity(in.body, point);
  const Eigen::Vector3d enu(
      Noisy(in, frame.east.dot(point), Param(in, gp::kHorizontalNoise), kPosition),
      Noisy(in, frame.north.dot(point), Param(in, gp::kHorizontalNoise), kPosition + 1),
      Noisy(in, frame.up.dot(point), Param(in, gp::kVerticalNoise), kPosition + 2));
  const double velocity_sigma = Param(in, gp::kVelocityNoise);
  const Eigen::Vector3d geodetic =
      EnuToGeodetic(in.world->geodetic_origin.value_or(model::GeodeticOrigin{}), enu);
  return {1.0,
          enu.x(),
          enu.y(),
          enu.z(),
          Noisy(in, frame.east.dot(v), velocity_sigma, kVelocity),
          Noisy(in, frame.north.dot(v), velocity_sigma, kVelocity + 1),
          Noisy(in, frame.up.dot(v), velocity_sigma, kVelocity + 2),
          geodetic.x(),
          geodetic.y(),
          geodetic.z()};
}

std::vector<double> ReadEncoder(const SensorInput& in) {
  const JointReadout joint = in.engine->ReadJoint(in.sensor->joint);
  const double counts_per_radian =
      Param(in, model::encoder_param::kCountsPerRevolution) / (2.0 * M_PI);
  return {std::floor(joint.continuous_position[0] * counts_per_radian),
          joint.rate[0] * counts_per_radian};
}

std::vector<double> ReadLidar(const SensorInput& in) {
  const int rays = static_cast<int>(Param(in, lp::kRays));
  const int layers = static_cast<int>(Param(in, lp::kLayers));
  const double half_span = Param(in, lp::kHalfSpan);
  const double lowest = Param(in, lp::kLowestElevation);
  const double highest = Param(in, lp::kHighestElevation);
  const double min_range = Param(in, lp::kMinRange), range = Param(in, lp::kRange);
  const double sigma = Param(in, lp::kRangeNoise), dropout = Param(in, lp::kDropout);
  std::vector<double> values(static_cast<size_t>(rays) * static_cast<size_t>(layers));
  for (int layer = 0; layer < layers; ++layer) {
    const double elevation =
        layers == 1 ? 0.5 * (lowest + highest) : lowest + (highest - lowest) * layer / (layers - 1);
    for (int k = 0; k < rays; ++k) {
      // Azimuth as the Scanner's: around sensor z in its z-x plane;
      // elevation towards sensor +y.
      const double azimuth = rays == 1 ? 0.0 : -half_span + 2.0 * half_span * k / (rays - 1);
      const Eigen::Vector3d direction =
          in.mount.linear() * Eigen::Vector3d(std::cos(elevation) * std::sin(azimuth),
                                              std::sin(elevation),
                                              std::cos(elevation) * std::cos(azimuth));
      const int ray = layer * rays + k;
      double distance = in.engine->CastRay(in.mount.translation(), direction, range, in.sensor->body);
      const bool lost = dropout > 0.0 && in.noise->Uniform(in.index, in.step, 2 * ray + 1) < dropout;
      if (distance >= range || distance < min_range || lost)
        distance = range;  // no return: max range, as the Scanner reports it
      else
        distance = std::clamp(Noisy(in, distance, sigma, 2 * ray), min_range, range);
      values[static_cast<size_t>(ray)] = distance;
    }
  }
  return values;
}

std::vector<double> ReadContact(const SensorInput& in) {
  const Eigen::Vector3d& force = in.body.contact_force;
  const double magnitude = force.norm();
  const bool touching = magnitude > Param(in, model::contact_param::kThreshold);
  return {touching ? 1.0 : 0.0, magnitude, force.x(), force.y(), force.z()};
}

}  // namespace simpartner::sim
