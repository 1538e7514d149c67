// The sensor kinds of sensor_t.KIND_* as every program names them: the
// word people read (simpartner-cmd, the sequencer's messages), the name
// the logger stores (Sensor.type), how many values one reading on
// SIM_SENSOR has and what each is called (sensor_reading_t.lcm gives their
// layout; the names head simpartner-query's CSV columns).
#pragma once

#include <string>
#include <vector>

#include "simpartner/sensor_t.hpp"

namespace simpartner {

struct SensorKindSpelling {
  int kind;              // sensor_t.KIND_*
  const char* word;      // "echo", "imu", "force/torque"
  const char* database;  // "ECHO", "IMU", "FORCE_TORQUE"
  // The values of one reading, space-separated ("ax ay az ..."); for a
  // Scanner and a Lidar "range", one per ray (a Lidar's row is a layer);
  // "" for an Echo (text) and a Camera (no readings).
  const char* columns;
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

// A reading's values as a table: a Lidar's layers x rays (layer-major,
// lowest layer first), a Scanner's 1 x rays, else 1 x ReadingSize.
struct ReadingShape {
  int rows = 1;
  int columns = 0;
};
ReadingShape ShapeOfReading(const sensor_t& sensor);

// The names of one row's values (ShapeOfReading(sensor).columns of them):
// the kind's columns, and for a Scanner or Lidar "range_0", "range_1", ...
std::vector<std::string> ReadingColumns(const sensor_t& sensor);

}  // namespace simpartner
