#include "simpartner/sensor_kinds.h"

#include <sstream>

namespace simpartner {

const std::vector<SensorKindSpelling>& SensorKindSpellings() {
  static const std::vector<SensorKindSpelling> kSpellings = {
      {sensor_t::KIND_ECHO, "echo", "ECHO", ""},
      {sensor_t::KIND_POSITION, "position", "POSITION", "x y z qw qx qy qz"},
      {sensor_t::KIND_SCANNER, "scanner", "SCANNER", "range"},
      {sensor_t::KIND_VELOCITY, "velocity", "VELOCITY", "vx vy vz wx wy wz"},
      {sensor_t::KIND_FORCE_TORQUE, "force/torque", "FORCE_TORQUE", "fx fy fz tx ty tz"},
      {sensor_t::KIND_IMU, "imu", "IMU", "ax ay az wx wy wz qw qx qy qz"},
      {sensor_t::KIND_GNSS, "gnss", "GNSS",
       "fix east north up v_east v_north v_up latitude longitude altitude"},
      {sensor_t::KIND_ENCODER, "encoder", "ENCODER", "count count_rate"},
      {sensor_t::KIND_LIDAR, "lidar", "LIDAR", "range"},
      {sensor_t::KIND_CONTACT, "contact", "CONTACT", "touching force fx fy fz"},
      {sensor_t::KIND_CAMERA, "camera", "CAMERA", ""},
  };
  return kSpellings;
}

const SensorKindSpelling& SpellSensorKind(int kind) {
  static const SensorKindSpelling kUnknown = {-1, "sensor kind", "UNKNOWN", ""};
  for (const SensorKindSpelling& s : SensorKindSpellings())
    if (s.kind == kind) return s;
  return kUnknown;
}

namespace {

// Parameter k of `sensor` as a whole number, or `fallback` when it has none.
int Param(const sensor_t& sensor, int k, int fallback) {
  return sensor.num_params > k && sensor.params.size() > static_cast<size_t>(k)
             ? static_cast<int>(sensor.params[static_cast<size_t>(k)])
             : fallback;
}

// Scanner parameters: rays, ...; Lidar: rays, halfSpan, layers, ...
int Rays(const sensor_t& sensor) {
  return Param(sensor, 0, sensor.kind == sensor_t::KIND_LIDAR ? 360 : 11);
}
int Layers(const sensor_t& sensor) { return Param(sensor, 2, 16); }

}  // namespace

int ReadingSize(const sensor_t& sensor) {
  switch (sensor.kind) {
    case sensor_t::KIND_SCANNER: return Rays(sensor);
    case sensor_t::KIND_LIDAR: return Rays(sensor) * Layers(sensor);
    default: return static_cast<int>(ReadingColumns(sensor).size());  // echo, camera: 0
  }
}

ReadingShape ShapeOfReading(const sensor_t& sensor) {
  if (sensor.kind == sensor_t::KIND_LIDAR) return {Layers(sensor), Rays(sensor)};
  return {1, ReadingSize(sensor)};
}

std::vector<std::string> ReadingColumns(const sensor_t& sensor) {
  std::vector<std::string> names;
  if (sensor.kind == sensor_t::KIND_SCANNER || sensor.kind == sensor_t::KIND_LIDAR) {
    for (int ray = 0; ray < Rays(sensor); ++ray) names.push_back("range_" + std::to_string(ray));
    return names;
  }
  std::istringstream words(SpellSensorKind(sensor.kind).columns);
  for (std::string word; words >> word;) names.push_back(word);
  return names;
}

}  // namespace simpartner
