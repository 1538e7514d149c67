// A logged simulation read into arrays, for Python's read_logged and the
// plots: per body its pose (and velocity) and contact force, per joint its
// state with continuous angles, each an array of steps x columns over the
// logged steps of a time range. Reads about 40 times faster than the
// row-by-row export (logger/README.md, "Reading a run back").
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

// Which bodies or joints to read.
struct PartSelection {
  bool all = true;
  std::vector<std::string> names;  // when !all: only these (an unknown name is an Error)
};

struct LoggedRunRequest {
  // Simulation.simulationID, "last" or "running" (simulations.h).
  std::string simulation = "last";
  // Only steps with from <= simulationTime <= to [s].
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
  PartSelection bodies, joints;
  bool poses = true;         // x_m ... angle_rad (ExportColumns of kPoses)
  bool velocities = false;   // poses: and vx, vy, vz by central differences of x, y, z
  bool forces = false;       // Fx_N ... Tz_Nm (kForces)
  bool joint_states = true;  // anchor_x_m ... T1z_Nm (kJoints), rotational angles continuous
};

// One body's or joint's numbers: values[step * columns + column], NaN
// where nothing was logged.
struct PartArray {
  std::string name;
  std::vector<double> values;
};

struct LoggedRun {
  uint32_t simulation = 0;   // Simulation.simulationID
  std::string engine;        // Simulation.engine: "ode" or "mujoco"
  std::vector<double> time;  // simulationTime [s] of each step read
  std::vector<int64_t> step;
  std::vector<PartArray> poses, forces, joints;  // bus order; empty when not asked for
};

// Throws Error for an unknown simulation, body or joint (with a
// did-you-mean) or an empty time range, DbError for the database. Opens a
// second connection to db's server for the time of the read.
LoggedRun ReadLoggedRun(DbConnection* db, const LoggedRunRequest& request);

}  // namespace simpartner::logger
