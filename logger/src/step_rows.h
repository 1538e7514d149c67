// One simulation's steps of a run as rows: which steps are new, which are in
// the database already (whole, or without all their rows), which never
// came (LogGap), then SimulationRow and the per-step Pose, ForceAndTorque,
// JointPose and WheelSoil rows.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "simpartner/logger/db.h"
#include "simpartner/logger/record.h"
#include "simpartner/logger/writer.h"
#include "simpartner/state_t.hpp"

namespace simpartner::logger {

// A state or a gap record of a run, in arrival order.
struct RunItem {
  state_t state;
  bool is_gap = false;
  GapPayload gap;
};

// The steps of a run's states, and the size of its states.
struct StepSpan {
  bool any_state = false;
  int64_t lo = 0, hi = 0;
  size_t bodies = 0, joints = 0;  // of the first state
};
StepSpan SpanOf(const std::vector<RunItem>& items);
// " WHERE simulationID = S AND step BETWEEN lo AND hi"
std::string StepRange(uint32_t simulation, const StepSpan& span);

// Steps already in the database with all their rows, and steps whose
// SimulationRow is there without all of its rows (left by a logger before
// transactions covered every failure): those get their rows.
struct StepPresence {
  std::set<int64_t> present;
  std::unordered_map<int64_t, int64_t> incomplete;  // step -> simulationRowID
};
StepPresence ReadPresence(DbConnection* db, uint32_t simulation, const StepSpan& span);

struct GapRow {
  int64_t first_step = 0, last_step = 0, missing = 0;
  std::string reason;
};

// What to write of a run: the gaps in order, the states that are new and
// those to complete, and the last step known afterwards.
struct StepPlan {
  std::vector<GapRow> gaps;
  std::vector<const state_t*> fresh, repaired;
  int64_t last_step = -1;
  uint64_t states_present = 0;  // skipped: in the database (or the run) already
};
// last_step: the last step known before (-1: none); stride: steps between
// logged states. Pointers into `items`.
StepPlan PlanSteps(const std::vector<RunItem>& items, int64_t last_step, int stride,
                   const StepPresence& presence);

// LogGap rows (replacing a row of the same first step); returns the rows.
uint64_t InsertGaps(DbConnection* db, uint32_t simulation, const std::vector<GapRow>& gaps);
// SimulationRow rows of `states`; adds their simulationRowIDs (by step)
// to *row_ids. Returns the rows.
uint64_t InsertSimulationRows(DbConnection* db, uint32_t simulation, const StepSpan& span,
                              const std::vector<const state_t*>& states,
                              std::unordered_map<int64_t, int64_t>* row_ids);

// The per-step rows of `states` in one sink per table. keep_existing: rows
// already there stay as they are (a repaired step). Returns the rows.
struct StateRowsTarget {
  const std::unordered_map<int64_t, int64_t>& row_ids;  // step -> simulationRowID
  const std::vector<int64_t>& body_ids;                 // by bus index
  const std::vector<int64_t>& joint_ids;
  InsertMethod method;
  const std::string& scratch_dir;
  bool keep_existing;
};
uint64_t InsertStateRows(DbConnection* db, const std::vector<const state_t*>& states,
                         const StateRowsTarget& target);

}  // namespace simpartner::logger
