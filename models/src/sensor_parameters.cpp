#include "simpartner/model/sensor_parameters.h"

#include <cmath>

namespace simpartner::model {
namespace {

// The noise parameters are datasheet figures; 0 (the default) is no noise.
const std::vector<SensorParameterSpec> kImu = {
    {"accelNoiseDensity", "m/s^2/sqrt(Hz)", 0.0, 0.0, 10.0},
    {"accelBiasX", "m/s^2", 0.0, -100.0, 100.0},
    {"accelBiasY", "m/s^2", 0.0, -100.0, 100.0},
    {"accelBiasZ", "m/s^2", 0.0, -100.0, 100.0},
    {"accelBiasRandomWalk", "m/s^3/sqrt(Hz)", 0.0, 0.0, 10.0},
    {"gyroNoiseDensity", "rad/s/sqrt(Hz)", 0.0, 0.0, 10.0},
    {"gyroBiasX", "rad/s", 0.0, -10.0, 10.0},
    {"gyroBiasY", "rad/s", 0.0, -10.0, 10.0},
    {"gyroBiasZ", "rad/s", 0.0, -10.0, 10.0},
    {"gyroBiasRandomWalk", "rad/s^2/sqrt(Hz)", 0.0, 0.0, 10.0},
};
const std::vector<SensorParameterSpec> kGnss = {
    {"horizontalNoise", "m", 0.0, 0.0, 1e4},
    {"verticalNoise", "m", 0.0, 0.0, 1e4},
    {"velocityNoise", "m/s", 0.0, 0.0, 1e3},
    {"coverHeight", "m", 0.0, 0.0, 1e4},
};
const std::vector<SensorParameterSpec> kEncoder = {
    {"countsPerRevolution", "", 1024.0, 1.0, 1e9, false, true},
};
const std::vector<SensorParameterSpec> kLidar = {
    {"rays", "", 360.0, 1.0, 10000.0, false, true},
    {"halfSpan", "rad", M_PI, 0.0, M_PI},
    {"layers", "", 16.0, 1.0, 1024.0, false, true},
    {"lowestElevation", "rad", -0.2617993877991494, -M_PI / 2, M_PI / 2},
    {"highestElevation", "rad", 0.2617993877991494, -M_PI / 2, M_PI / 2},
    {"minRange", "m", 0.0, 0.0, 1e4},
    {"range", "m", 100.0, 0.0, 1e4, true},
    {"rangeNoise", "m", 0.0, 0.0, 100.0},
    {"dropout", "", 0.0, 0.0, 1.0},
};
const std::vector<SensorParameterSpec> kContact = {
    {"threshold", "N", 0.0, 0.0, 1e9},
};
const std::vector<SensorParameterSpec> kNone;

}  // namespace

const std::vector<SensorParameterSpec>& SensorParameterSpecs(SensorKind kind) {
  switch (kind) {
    case SensorKind::kImu: return kImu;
    case SensorKind::kGnss: return kGnss;
    case SensorKind::kEncoder: return kEncoder;
    case SensorKind::kLidar: return kLidar;
    case SensorKind::kContact: return kContact;
    default: return kNone;
  }
}

int SensorParameterIndex(SensorKind kind, const std::string& name) {
  const std::vector<SensorParameterSpec>& specs = SensorParameterSpecs(kind);
  for (size_t k = 0; k < specs.size(); ++k)
    if (name == specs[k].name) return static_cast<int>(k);
  return -1;
}

std::vector<double> DefaultSensorParameters(SensorKind kind) {
  std::vector<double> values;
  for (const SensorParameterSpec& spec : SensorParameterSpecs(kind))
    values.push_back(spec.default_value);
  return values;
}

bool MeasuresJoint(SensorKind kind) {
  return kind == SensorKind::kForceTorque || kind == SensorKind::kEncoder;
}

bool NeedsRate(SensorKind kind) { return !SensorParameterSpecs(kind).empty(); }

}  // namespace simpartner::model
