// The parameters of the field sensor kinds (Imu, Gnss,
// Encoder, Lidar, Contact): one table per kind gives each parameter's name
// in the robot file, unit, default and accepted range. The loader checks
// files against it, SIM_MODEL carries the values in its order
// (sensor_t.params), and docs/sensors.md lists it. The thesis's kinds
// keep their own fields (the Scanner's rays, halfSpan, range).
#pragma once

#include <string>
#include <vector>

#include "simpartner/model/model.h"

namespace simpartner::model {

struct SensorParameterSpec {
  const char* name;        // <parameter name="...">
  const char* unit;        // "" for a plain number
  double default_value;
  double min;              // accepted range [min, max] ...
  double max;
  bool min_open = false;   // ... or (min, max]
  bool whole = false;      // a whole number
};

// Empty for the thesis's kinds.
const std::vector<SensorParameterSpec>& SensorParameterSpecs(SensorKind kind);
// Index of `name` among the kind's parameters, or -1.
int SensorParameterIndex(SensorKind kind, const std::string& name);
// The defaults, in table order.
std::vector<double> DefaultSensorParameters(SensorKind kind);
// Whether the kind measures a joint (<jointRef>) rather than a body.
bool MeasuresJoint(SensorKind kind);
// Whether the kind samples at its rate (the new kinds): its rate must be > 0.
bool NeedsRate(SensorKind kind);

// Indices into Sensor::parameters, per kind, in table order.
namespace imu_param {
enum : int {
  kAccelNoiseDensity, kAccelBiasX, kAccelBiasY, kAccelBiasZ, kAccelBiasRandomWalk,
  kGyroNoiseDensity, kGyroBiasX, kGyroBiasY, kGyroBiasZ, kGyroBiasRandomWalk, kCount
};
}
namespace gnss_param {
enum : int { kHorizontalNoise, kVerticalNoise, kVelocityNoise, kCoverHeight, kCount };
}
namespace encoder_param {
enum : int { kCountsPerRevolution, kCount };
}
namespace lidar_param {
enum : int {
  kRays, kHalfSpan, kLayers, kLowestElevation, kHighestElevation, kMinRange, kRange,
  kRangeNoise, kDropout, kCount
};
}
namespace contact_param {
enum : int { kThreshold, kCount };
}

}  // namespace simpartner::model
