// simpartner-query: what is in the database, for people and for
// spreadsheets, Octave or Python: the list of simulations, one
// simulation's poses, contact forces or joint states as CSV (SI units,
// shortest exact numbers) or as a gnuplot plot, and, for an administrator,
// deleting simulations.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "simpartner/logger/db.h"
#include "simpartner/plot.h"

namespace simpartner::logger {

enum class ExportKind { kPoses, kForces, kJoints };

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

// A table of the simulations, newest last.
void ListSimulations(DbConnection* db, std::ostream& out);
// CSV with a header line; returns the number of data rows. Throws Error for
// an unknown simulation, DbError for the database. With velocities, a first
// line starting with '#' says how they were obtained.
uint64_t ExportCsv(DbConnection* db, const ExportRequest& request, std::ostream& out);

enum class PlotKind {
  kPosition,     // a body's x, y, z against time
  kVelocity,     // a body's vx, vy, vz against time (central differences)
  kAngle,        // a joint's angle (continuous) against time
  kRate,         // a joint's rate
  kForce,        // a joint's constraint force on body1 (components and magnitude)
  kWheelForces,  // the contact force along "up" (against gravity) of every wheel
  kTrack,        // a body's x-z track seen from above (equal axes)
};

// "position", "velocity", "angle", "rate", "force", "wheel-forces", "track";
// throws Error naming the word and the kinds (with a did-you-mean).
PlotKind ParsePlotKind(const std::string& word);

struct PlotRequest {
  PlotKind kind = PlotKind::kPosition;
  std::string simulation = "last";
  std::string name;  // the body or joint; wheel-forces: "" = every body named Wheel*
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
};

// The plot's series from the database (title names the simulation).
// Throws as ReadExport, and Error when the body or joint is missing.
Plot MakePlot(DbConnection* db, const PlotRequest& request);

// What delete and prune removed.
struct DeleteSummary {
  std::vector<uint32_t> simulations;
  uint64_t steps = 0;  // SimulationRow rows
};

// Deletes one simulation (every row of every table that belongs to it) in
// one transaction. Needs DELETE (the administrator; the logger and reader
// users have none): without it, throws Error saying so and nothing is
// deleted. An open simulation is refused unless `even_if_open`.
DeleteSummary DeleteSimulation(DbConnection* db, const std::string& simulation, bool even_if_open);
// Deletes all but the newest `keep` simulations (open ones are kept and
// count among them).
DeleteSummary PruneSimulations(DbConnection* db, int64_t keep);

// The tables that get rows every logged step.
const std::vector<std::string>& PerStepTables();

// The size of one per-step table on the server.
struct TableStorage {
  std::string table;
  uint64_t rows = 0;           // InnoDB's estimate
  uint64_t logical_bytes = 0;  // data_length + index_length: pages as InnoDB counts them
  uint64_t disk_bytes = 0;     // allocated in the file system (compressed pages take less)
  bool compressed = false;     // PAGE_COMPRESSED
};

// Writes the per-step tables' dirty pages to disk and reads their sizes.
// Needs the administrator (FLUSH TABLES, information_schema.INNODB_SYS_TABLESPACES).
std::vector<TableStorage> ReadTableStorage(DbConnection* db);
// Whether information_schema.TABLES.CREATE_OPTIONS (lower case) asks for
// page compression.
bool PageCompressedOption(const std::string& create_options);

// Switches InnoDB page compression (zlib, MariaDB's PAGE_COMPRESSED) of the
// per-step tables on or off. Rebuilds each table, rows already logged
// included; a running logger waits meanwhile. The columns stay as they are,
// so every query runs unchanged. Needs the administrator (ALTER).
void SetPageCompression(DbConnection* db, bool on);

}  // namespace simpartner::logger
