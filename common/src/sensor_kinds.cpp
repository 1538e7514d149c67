#include "simpartner/sensor_kinds.h"

namespace simpartner {

const std::vector<SensorKindSpelling>& SensorKindSpellings() {
  static const std::vector<SensorKindSpelling> kSpellings = {
      {sensor_t::KIND_ECHO, "echo", "ECHO"},
      {sensor_t::KIND_POSITION, "position", "POSITION"},
      {sensor_t::KIND_SCANNER, "scanner", "SCANNER"},
      {sensor_t::KIND_VELOCITY, "velocity", "VELOCITY"},
      {sensor_t::KIND_FORCE_TORQUE, "force/torque", "FORCE_TORQUE"},
      {sensor_t::KIND_IMU, "imu", "IMU"},
      {sensor_t::KIND_GNSS, "gnss", "GNSS"},
      {sensor_t::KIND_ENCODER, "encoder", "ENCODER"},
      {sensor_t::KIND_LIDAR, "lidar", "LIDAR"},
      {sensor_t::KIND_CONTACT, "contact", "CONTACT"},
      {sensor_t::KIND_CAMERA, "camera", "CAMERA"},
  };
  return kSpellings;
}

const SensorKindSpelling& SpellSensorKind(int kind) {
  static const SensorKindSpelling kUnknown = {-1, "sensor kind", "UNKNOWN"};
  for (const SensorKindSpelling& s : SensorKindSpellings())
    if (s.kind == kind) return s;
  return kUnknown;
}

int ReadingSize(const sensor_t& sensor) {
  auto param = [&](int k, double fallback) {
    return sensor.num_params > k ? static_cast<int>(sensor.params[static_cast<size_t>(k)])
                                 : static_cast<int>(fallback);
  };
  switch (sensor.kind) {
    case sensor_t::KIND_POSITION: return 7;   // x y z qw qx qy qz
    case sensor_t::KIND_VELOCITY: return 6;   // v, w
    case sensor_t::KIND_FORCE_TORQUE: return 6;
    case sensor_t::KIND_SCANNER: return param(0, 11);  // rays
    case sensor_t::KIND_IMU: return 10;       // a, w, q
    case sensor_t::KIND_GNSS: return 10;      // fix, enu, v enu, lat lon alt
    case sensor_t::KIND_ENCODER: return 2;    // count, count rate
    case sensor_t::KIND_LIDAR: return param(0, 360) * param(2, 16);  // rays x layers
    case sensor_t::KIND_CONTACT: return 5;    // touching, |F|, F
    default: return 0;                        // echo: text; camera: images elsewhere
  }
}

}  // namespace simpartner
