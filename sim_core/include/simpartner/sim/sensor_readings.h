// The readings of the field sensor kinds (Imu, Gnss, Encoder, Lidar,
// Contact), with their noise. Value layouts: docs/sensors.md and
// lcmtypes/sensor_reading_t.lcm. The thesis's kinds stay in simulation.cpp.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "simpartner/sim/sensor_noise.h"
#include "simpartner/model/flat_model.h"
#include "simpartner/sim/engine.h"

namespace simpartner::sim {

// What a reading at one step is made from.
struct SensorInput {
  PhysicsEngine* engine = nullptr;
  const model::FlatSensor* sensor = nullptr;
  const model::World* world = nullptr;
  const SensorNoise* noise = nullptr;
  int index = 0;                   // the sensor's index: part of its noise key
  int64_t step = 0;
  double rate = 0.0;               // [Hz] it samples at now
  BodyReadout body;                // its body (sensor->body)
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // in the world
};

// An IMU's memory between steps: the mount point's velocity before the
// last step, and the random walks of its biases.
struct ImuMemory {
  Eigen::Vector3d previous_velocity = Eigen::Vector3d::Zero();  // world
  Eigen::Vector3d accel_walk = Eigen::Vector3d::Zero();         // sensor frame
  Eigen::Vector3d gyro_walk = Eigen::Vector3d::Zero();
};

// Velocity of a point fixed to the body, in the world.
Eigen::Vector3d PointVelocity(const BodyReadout& body, const Eigen::Vector3d& point);
// Advances the bias random walks by one step of `stepsize` (a no-op when
// the sensor has none), with the noise of `step` (the step just taken).
void WalkImuBias(const model::Sensor& sensor, const SensorNoise& noise, int index, int64_t step,
                 double stepsize, ImuMemory* memory);

std::vector<double> ReadImu(const SensorInput& in, const ImuMemory& memory, double stepsize);
std::vector<double> ReadGnss(const SensorInput& in);
std::vector<double> ReadEncoder(const SensorInput& in);
std::vector<double> ReadLidar(const SensorInput& in);
std::vector<double> ReadContact(const SensorInput& in);

}  // namespace simpartner::sim
