// Reads per-step tables (Pose, ForceAndTorque, JointPose) of one
// simulation into arrays, fast: in the binary protocol (db.h QueryBinary),
// in chunks of steps on two connections, so that the server sends one chunk
// while the other is stored into the arrays, and without ORDER BY (each
// row goes to its place by its simulationRowID and part id).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

// The logged steps of a time range in step order, and where each
// simulationRowID goes.
class StepIndex {
 public:
  // Steps with from <= simulationTime <= to.
  static StepIndex Read(DbConnection* db, uint32_t simulation, double from, double to);

  size_t size() const { return time_.size(); }
  const std::vector<double>& time() const { return time_; }
  const std::vector<int64_t>& step() const { return step_; }
  // The index of a simulationRowID, or -1 when it is not one of these steps.
  int64_t IndexOf(uint64_t row_id) const;

 private:
  void BuildLookup(const std::vector<uint64_t>& row_ids);

  std::vector<double> time_;
  std::vector<int64_t> step_;
  // simulationRowIDs are mostly consecutive: a dense table from the
  // smallest, or a hash map when another simulation's rows lie between.
  uint64_t first_row_ = 0;
  std::vector<int32_t> dense_;
  std::unordered_map<uint64_t, int64_t> sparse_;
};

// One table to read: its `columns` of the parts (bodies or joints) with
// ids `ids` (ids[i] fills arrays[i]), `steps x columns` each, NaN where a
// row or value is missing.
struct StepTableFetch {
  std::string table;      // "Pose"
  std::string id_column;  // "bodyID"
  std::vector<std::string> columns;
  std::vector<int64_t> ids;
  bool every_part = true;  // ids are all of the simulation's: no filter on them
  std::vector<std::vector<double>> arrays;
};

// Fills the arrays of every fetch. Opens a second connection to db's
// server (same option file and database). Throws DbError.
void FetchStepTables(DbConnection* db, uint32_t simulation, const StepIndex& steps,
                     std::vector<StepTableFetch>* fetches);

}  // namespace simpartner::logger
