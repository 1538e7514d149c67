// Writes records into the database: a model becomes a Simulation with its
// Robot, Body, Joint, Sensor, Actuator and RobotComponent rows; states
// become SimulationRow, Pose, ForceAndTorque and JointPose rows, many steps
// per transaction, as multi-row INSERTs or LOAD DATA LOCAL files. A
// transaction is committed whole or rolled back, whatever fails (the
// server, the connection, the LOAD DATA scratch file: then the batch goes
// again as INSERTs). Every write is idempotent, keyed by (simulation, step,
// body/joint): a step that is already in the database with all its rows is
// skipped (one with its SimulationRow but not all its rows gets the rest),
// so after any failure the same records can simply be written again (a
// replayed spool, a restarted logger) without duplicate rows. Steps that
// never came, or that the receiver could not keep, go into LogGap with the
// reason.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/logger/db.h"
#include "simpartner/logger/record.h"

namespace simpartner::logger {

enum class InsertMethod {
  kMultiRowInsert,  // INSERT INTO t VALUES (...),(...) up to ~1 MB per statement
  kLoadDataLocal,   // LOAD DATA LOCAL INFILE of a file written per table and batch
  // INSERT for small batches (keeping up at real time), LOAD DATA LOCAL for
  // big ones (catching up), where it costs the server a quarter less per
  // row; INSERT only if the server refuses LOAD DATA LOCAL.
  kAuto,
};
const char* InsertMethodName(InsertMethod method);

struct WriterOptions {
  InsertMethod method = InsertMethod::kAuto;
  std::string lcm_url;      // recorded in Simulation.lcmUrl
  int log_interval = 1;     // recorded in Simulation.logInterval
  std::string scratch_dir;  // where LOAD DATA files are written
  std::string tag;          // Simulation.tag ("" = NULL)
};

// LogGap.reason of steps that never reached the logger.
inline constexpr const char* kGapNotReceived =
    "never received (lost on the bus, or sent while no logger ran)";

struct WriteResult {
  uint64_t states_written = 0;
  uint64_t states_present = 0;  // already in the database: skipped
  uint64_t rows_written = 0;    // all tables
  uint64_t gaps = 0;            // LogGap rows
  uint64_t missing_steps = 0;
  uint64_t states_repaired = 0; // had their SimulationRow but not all rows: completed
  uint64_t unwritable = 0;      // records of a simulation whose model never came
  std::vector<int64_t> lags_us; // commit time minus publish time, per state written
};

struct RunItem;  // a state or gap record of a run (step_rows.h)

class DbWriter {
 public:
  using Notice = std::function<void(const std::string&)>;
  DbWriter(DbTarget target, WriterOptions options, Notice notice);
  ~DbWriter();

  // Writes the records in order: connects (bringing the schema up to date)
  // if needed, then one transaction per model or end-of-simulation record
  // and one for each run of state, sensor and command records between them.
  // Throws DbError; the connection is dropped if it broke. Records already
  // committed stay committed; writing the same records again is harmless.
  WriteResult Write(const std::vector<Record>& records);

  bool connected() const { return db_ != nullptr; }
  void Connect();
  void Disconnect();
  const DbTarget& target() const { return target_; }

 private:
  struct SimInfo {
    uint32_t id = 0;           // Simulation.simulationID
    int64_t bus_id = 0;
    int stride = 1;            // steps between logged states
    int64_t last_step = -1;    // last step known in the database
    std::vector<int64_t> robot_ids, body_ids, joint_ids, sensor_ids;
  };
  struct RunRecords;  // a run's records sorted by what they become (writer.cpp)

  void WriteModel(const Record& record, WriteResult* result);
  // Reopens a simulation the logger before this one closed as silent;
  // whether it did.
  bool ReopenSilent(uint32_t simulation);
  void CloseSimulation(const Record& record);
  // Undoes a close: the sim of a simulation closed as silent was heard again.
  void ReopenSimulation(const Record& record);
  // check_present: look up which steps are already there first. Without
  // it, steps above the last one committed are taken as new, and a
  // duplicate key (someone else wrote them) makes the caller retry with it.
  // force_insert: no LOAD DATA (its scratch file could not be written).
  void WriteRun(const std::vector<const Record*>& run, bool check_present, bool force_insert,
                WriteResult* result);
  // A run's states and gaps by simulation and its other records; records
  // of an unknown simulation are counted in result->unwritable.
  RunRecords SortRun(const std::vector<const Record*>& run, WriteResult* result);
  // One simulation's states and gaps of a run, counted into *pending,
  // with the publish times of the states written added to *published;
  // returns the last step known afterwards.
  int64_t WriteSteps(const SimInfo& sim, const std::vector<RunItem>& items, bool check_present,
                     bool force_insert, WriteResult* pending, std::vector<int64_t>* published);
  // WriteRun in one transaction, again after a rollback where that can
  // succeed (duplicate key, LOAD DATA refused or its file unwritable).
  void WriteRunAtomically(const std::vector<const Record*>& run, WriteResult* result);
  SimInfo* FindSimulation(int64_t bus_id);
  bool LoadSimulation(const std::string& where, SimInfo* info);
  void CloseOthers(const SimInfo& keep, const std::string& host, const std::string& reason);
  // Method for the per-step tables of a batch of `steps` steps.
  InsertMethod MethodFor(size_t steps) const;

  DbTarget target_;
  WriterOptions options_;
  Notice notice_;
  std::unique_ptr<DbConnection> db_;
  std::map<int64_t, SimInfo> simulations_;  // by bus simulation id
  bool load_data_refused_ = false;          // kAuto fell back to INSERT
  uint64_t scratch_failures_ = 0;           // batches whose LOAD DATA file could not be written
  std::chrono::steady_clock::time_point last_scratch_notice_{};
};

}  // namespace simpartner::logger
