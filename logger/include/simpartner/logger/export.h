// One logged simulation's poses, contact forces or joint states step by
// step, for the CSV of simpartner-query (SI units, shortest exact numbers):
// a time range, every Nth step, body velocities by central differences and
// continuous joint angles.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

enum class ExportKind { kPoses, kForces, kJoints };

// How many numbers a body's pose, a body's force and a joint's state have
// (ExportColumns after time, step and name), and where a joint's angles
// start among its numbers (after its anchor x, y, z). A joint read with
// its stored continuous angles has three more at the end.
inline constexpr size_t kPoseColumns = 7, kForceColumns = 6, kJointColumns = 15;
inline constexpr size_t kJointAngleColumn = 3;

struct ExportRequest {
  ExportKind kind = ExportKind::kPoses;
  // Simulation.simulationID, "last" (the newest) or "running" (the newest
  // still open, i.e. without endTime).
  std::string simulation = "last";
  std::string name;  // only this body (poses, forces) or joint; "" = all
  // Only steps with from <= simulationTime <= to [s].
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
  int64_t every = 1;        // every Nth logged step of the range (its first kept)
  bool velocities = false;  // poses: vx, vy, vz by central differences of x, y, z
  bool unwrap = false;      // joints: rotational angles continuous (no jump at +-pi)
};

// One logged step of an export: per body or joint its name and numbers in
// the order of ExportColumns (after time and step).
struct ExportRow {
  std::string name;
  std::vector<double> values;
};
struct ExportStep {
  double time = 0;
  int64_t step = 0;
  std::vector<ExportRow> rows;
};

// The numeric column names of a request (without time_s, step and the name).
std::vector<std::string> ExportColumns(const ExportRequest& request);

// Every kept step in order. Throws Error for an unknown simulation, body or
// joint (with a did-you-mean), or a bad request; DbError for the database.
// Returns the simulationID read.
uint32_t ReadExport(DbConnection* db, const ExportRequest& request,
                    const std::function<void(const ExportStep&)>& sink);

// CSV with a header line; returns the number of data rows. Throws Error for
// an unknown simulation, DbError for the database. With velocities, a first
// line starting with '#' says how they were obtained.
uint64_t ExportCsv(DbConnection* db, const ExportRequest& request, std::ostream& out);

// Logged sensor readings (SensorReading) of one simulation, for
// `simpartner-query readings`.
struct ReadingsRequest {
  std::string simulation = "last";  // as ExportRequest.simulation
  std::string sensor;               // only this sensor (wide CSV); "" = every sensor (long CSV)
  // Only readings with from <= simulationTime <= to [s].
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
};

// CSV of the readings in step order; returns the number of data rows.
// One sensor: "wide", time_s, step, sensor, then the values under the names
// of its kind (sensor_kinds.h: ax, ay, ... for an Imu); a Scanner or Lidar
// gets one row per layer, "layer" (lowest first) then range_0 .. range_N-1;
// an Echo its text. Every sensor: "long", one row per value: time_s, step,
// sensor, kind, layer (0 but for a lidar), column (the value's name),
// value. Non-finite values are NULL, as in the database. Throws Error for
// an unknown simulation or sensor (with a did-you-mean), DbError.
uint64_t ExportReadingsCsv(DbConnection* db, const ReadingsRequest& request, std::ostream& out);

}  // namespace simpartner::logger
