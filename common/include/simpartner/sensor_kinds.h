// The sensor kinds of sensor_t.KIND_* as every program names them: the
// word people read (simpartner-cmd, the sequencer's messages), the name
// the logger stores (Sensor.type), and how many values one reading on
// SIM_SENSOR has (sensor_reading_t.lcm gives their layout).
#pragma once

#include <vector>

#include "simpartner/sensor_t.hpp"

namespace simpartner {

struct SensorKindSpelling {
  int kind;              // sensor_t.KIND_*
  const char* word;      // "echo", "imu", "force/torque"
  const char* database;  // "ECHO", "IMU", "FORCE_TORQUE"
};

// Every kind, in sensor_t.KIND_* order.
const std::vector<SensorKindSpelling>& SensorKindSpellings();

// The spellings of kind; for a kind outside the table, "sensor kind" and
// "UNKNOWN".
const SensorKindSpelling& SpellSensorKind(int kind);

// The values in one reading of `sensor`: fixed per kind, a Scanner's rays
// and a Lidar's layers x rays from its parameters; 0 for an Echo (text) and
// a Camera (no SIM_SENSOR readings: images on SIM_IMAGE).
int ReadingSize(const sensor_t& sensor);

}  // namespace simpartner
