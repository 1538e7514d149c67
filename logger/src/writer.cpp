#include "simpartner/logger/writer.h"

#include <cppconn/exception.h>

#include <algorithm>
#include <chrono>
#include <numeric>

#include "decode_record.h"
#include "event_rows.h"
#include "model_rows.h"
#include "row_sink.h"
#include "simpartner/logger/schema.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/model_t.hpp"
#include "step_rows.h"
#include "writer_text.h"
#include "simpartner/sender.h"

namespace simpartner::logger {
namespace {

// The last step of a simulation in the database, -1 if none.
int64_t LastLoggedStep(DbConnection* db, uint32_t simulation) {
  return db->QueryInt("SELECT MAX(step) FROM SimulationRow WHERE simulationID = " +
                          std::to_string(simulation),
                      "SELECT MAX(step) FROM SimulationRow", -1);
}

constexpr int kDuplicateKey = 1062;  // ER_DUP_ENTRY
// Below this many steps a batch goes as INSERTs: LOAD DATA's fixed cost per
// statement (a file per table) outweighs its cheaper rows.
constexpr size_t kLoadDataMinSteps = 25;

// The server or the client library will not do LOAD DATA LOCAL.
bool IsLoadDataRefused(int code) {
  return code == 1148 /* ER_NOT_ALLOWED_COMMAND */ || code == 4166 /* capability disabled */ ||
         code == 2068 /* CR_LOAD_DATA_LOCAL_INFILE_REJECTED */ || code == 3948;
}

bool IsBoundary(const Record& record) {
  return record.kind == RecordKind::kModel || record.kind == RecordKind::kSimulationEnded ||
         record.kind == RecordKind::kSimulationReopened;
}

// What a committed run adds to the result; lags from the publish times.
void AddCommitted(const WriteResult& pending, const std::vector<int64_t>& published,
                  WriteResult* result) {
  const int64_t committed = WallMicros();
  result->states_written += pending.states_written;
  result->states_present += pending.states_present;
  result->rows_written += pending.rows_written;
  result->gaps += pending.gaps;
  result->missing_steps += pending.missing_steps;
  result->states_repaired += pending.states_repaired;
  result->unwritable += pending.unwritable;
  for (int64_t p : published) result->lags_us.push_back(committed - p);
}

}  // namespace

const char* InsertMethodName(InsertMethod method) {
  switch (method) {
    case InsertMethod::kMultiRowInsert: return "multi-row INSERT";
    case InsertMethod::kLoadDataLocal: return "LOAD DATA LOCAL";
    case InsertMethod::kAuto: return "multi-row INSERT or LOAD DATA LOCAL by batch size";
  }
  return "?";
}

DbWriter::DbWriter(DbTarget target, WriterOptions options, Notice notice)
    : target_(std::move(target)), options_(std::move(options)), notice_(std::move(notice)) {}

DbWriter::~DbWriter() = default;

void DbWriter::Connect() {
  if (db_) return;
  std::unique_ptr<DbConnection> db =
      DbConnection::Open(target_, options_.method != InsertMethod::kMultiRowInsert);
  MigrateSchema(db.get(), notice_);
  // After a lost connection the database, not our memory, says how far each
  // simulation got: whatever the old connection sent last may or may not
  // have been committed. A step that went missing then shows as a gap.
  for (auto& [bus_id, sim] : simulations_) sim.last_step = LastLoggedStep(db.get(), sim.id);
  db_ = std::move(db);
}

void DbWriter::Disconnect() { db_.reset(); }

WriteResult DbWriter::Write(const std::vector<Record>& records) {
  WriteResult result;
  Connect();
  try {
    size_t i = 0;
    while (i < records.size()) {
      const Record& record = records[i];
      if (IsBoundary(record)) {
        if (record.kind == RecordKind::kModel) WriteModel(record, &result);
        else if (record.kind == RecordKind::kSimulationEnded) CloseSimulation(record);
        else ReopenSimulation(record);
        ++i;
        continue;
      }
      std::vector<const Record*> run;
      for (; i < records.size() && !IsBoundary(records[i]); ++i) run.push_back(&records[i]);
      WriteRunAtomically(run, &result);
    }
  } catch (const DbError& e) {
    if (db_) db_->Rollback();
    if (e.kind() == DbErrorKind::kUnreachable) db_.reset();
    throw;
  } catch (...) {
    // Whatever failed, the open transaction must not survive: the next
    // START TRANSACTION would commit it half done.
    if (db_) db_->Rollback();
    throw;
  }
  return result;
}

void DbWriter::WriteRunAtomically(const std::vector<const Record*>& run, WriteResult* result) {
  bool check_present = false;
  bool force_insert = false;
  while (true) {
    try {
      WriteRun(run, check_present, force_insert, result);
      return;
    } catch (const ScratchFileError& e) {
      db_->Rollback();
      if (force_insert) throw;
      force_insert = true;
      ++scratch_failures_;
      const auto now = std::chrono::steady_clock::now();
      if (scratch_failures_ == 1 || now - last_scratch_notice_ > std::chrono::seconds(10)) {
        last_scratch_notice_ = now;
        notice_(std::string(e.what()) + "; the batch was rolled back and goes as multi-row "
                "INSERTs (" + std::to_string(scratch_failures_) + " batches so far)");
      }
    } catch (const DbError& e) {
      db_->Rollback();
      if (e.code() == kDuplicateKey && !check_present) {
        check_present = true;
      } else if (options_.method == InsertMethod::kAuto && IsLoadDataRefused(e.code()) &&
                 !load_data_refused_) {
        load_data_refused_ = true;
        notice_("server " + target_.Server() + " refuses LOAD DATA LOCAL (" + e.cause() +
                "); using multi-row INSERTs only");
      } else {
        throw;
      }
    }
  }
}

bool DbWriter::LoadSimulation(const std::string& where, SimInfo* info) {
  std::unique_ptr<sql::ResultSet> rows = db_->Query(
      "SELECT simulationID, busSimulationID, stateEvery, logInterval FROM Simulation WHERE " +
          where + " ORDER BY simulationID DESC LIMIT 1",
      "SELECT FROM Simulation");
  try {
    if (!rows->next()) return false;
    info->id = rows->getUInt(1);
    info->bus_id = rows->getInt64(2);
    info->stride = std::lcm(std::max(1, rows->getInt(3)), std::max(1, rows->getInt(4)));
  } catch (const sql::SQLException&) {
    db_->Rethrow("read Simulation");
  }
  const std::string id = std::to_string(info->id);
  info->last_step = LastLoggedStep(db_.get(), info->id);
  const auto count = [&](const char* table) {
    return static_cast<size_t>(db_->QueryInt(
        std::string("SELECT COUNT(*) FROM ") + table + " WHERE simulationID = " + id,
        std::string("SELECT COUNT(*) FROM ") + table, 0));
  };
  info->robot_ids = LoadIds(db_.get(), "Robot", "robotID", info->id, count("Robot"));
  info->body_ids = LoadIds(db_.get(), "Body", "bodyID", info->id, count("Body"));
  info->joint_ids = LoadIds(db_.get(), "`Joint`", "jointID", info->id, count("`Joint`"));
  info->sensor_ids = LoadIds(db_.get(), "Sensor", "sensorID", info->id, count("Sensor"));
  return true;
}

InsertMethod DbWriter::MethodFor(size_t steps) const {
  if (options_.method != InsertMethod::kAuto) return options_.method;
  return steps >= kLoadDataMinSteps && !load_data_refused_ ? InsertMethod::kLoadDataLocal
                                                           : InsertMethod::kMultiRowInsert;
}

DbWriter::SimInfo* DbWriter::FindSimulation(int64_t bus_id) {
  auto it = simulations_.find(bus_id);
  if (it != simulations_.end()) return &it->second;
  SimInfo info;
  if (!LoadSimulation("busSimulationID = " + std::to_string(bus_id), &info)) return nullptr;
  // Records of a simulation logged before (a replayed spool, a restarted
  // logger) before its model came by again.
  notice_("resuming simulation " + std::to_string(info.id) + " (bus simulation id " +
          std::to_string(bus_id) + ", last logged step " + std::to_string(info.last_step) + ")");
  return &simulations_.emplace(bus_id, std::move(info)).first->second;
}

void DbWriter::CloseOthers(const SimInfo& keep, const std::string& host, const std::string& reason) {
  std::vector<uint32_t> open;
  std::unique_ptr<sql::ResultSet> rows = db_->Query(
      "SELECT simulationID FROM Simulation WHERE endTime IS NULL AND host = " + Quoted(host) +
          " AND lcmUrl = " + Quoted(options_.lcm_url) +
          " AND simulationID <> " + std::to_string(keep.id),
      "SELECT open simulations FROM Simulation");
  try {
    while (rows->next()) open.push_back(rows->getUInt(1));
  } catch (const sql::SQLException&) {
    db_->Rethrow("read Simulation");
  }
  for (uint32_t id : open) {
    const std::string sid = std::to_string(id);
    db_->Execute("UPDATE Simulation SET endTime = UTC_TIMESTAMP(6), endReason = " + Quoted(reason) +
                     ", lastStep = (SELECT MAX(step) FROM SimulationRow WHERE simulationID = " +
                     sid + ") WHERE simulationID = " + sid + " AND endTime IS NULL",
                 "UPDATE Simulation (close " + sid + ")");
    notice_("closed simulation " + sid + ": " + reason);
  }
}

void DbWriter::WriteModel(const Record& record, WriteResult* result) {
  model_t model;
  if (!DecodeRecord(record, &model, notice_)) {
    ++result->unwritable;
    return;
  }
  if (simulations_.count(model.simulation_id) > 0) return;  // announced again

  SimInfo info;
  db_->Begin();
  const bool resumed = LoadSimulation("busSimulationID = " + std::to_string(model.simulation_id) +
                                          " AND host = " + Quoted(model.host),
                                      &info);
  if (!resumed) {
    info.id = InsertSimulation(db_.get(), model, options_, record.received_us);
    info.bus_id = model.simulation_id;
    info.stride = std::lcm(std::max(1, model.state_every), std::max(1, options_.log_interval));
    info.last_step = -1;
    ModelIds ids = InsertModelRows(db_.get(), model, info.id);
    info.robot_ids = std::move(ids.robot_ids);
    info.body_ids = std::move(ids.body_ids);
    info.joint_ids = std::move(ids.joint_ids);
    info.sensor_ids = std::move(ids.sensor_ids);
  }
  const bool reopened = resumed && ReopenSilent(info.id);
  CloseOthers(info, model.host,
              "a new simulation started on the bus (the sim restarted or was reset)");
  db_->Commit();
  if (reopened)
    notice_("reopened simulation " + std::to_string(info.id) +
            ": its sim announced its model again after it was closed as silent");
  notice_(std::string(resumed ? "resuming" : "logging") + " simulation " +
          std::to_string(info.id) + " (bus simulation id " + std::to_string(model.simulation_id) +
          " from " + model.host + ", world '" + model.world_name + "', " +
          std::to_string(model.bodies.size()) + " bodies, " + std::to_string(model.joints.size()) +
          " joints" +
          (resumed ? ", last logged step " + std::to_string(info.last_step) : std::string()) + ")");
  simulations_[model.simulation_id] = std::move(info);
}

bool DbWriter::ReopenSilent(uint32_t simulation) {
  // Closed as silent by a logger before this one, but its sim talks: open
  // again (steps lost meanwhile show as a gap when states come).
  db_->Execute("UPDATE Simulation SET endTime = NULL, endReason = NULL, lastStep = NULL"
               " WHERE simulationID = " + std::to_string(simulation) + " AND endReason LIKE " +
               Quoted(std::string(kSilentReasonStart) + "%"),
               "UPDATE Simulation (reopen " + std::to_string(simulation) + ")");
  return db_->QueryInt("SELECT ROW_COUNT()", "SELECT ROW_COUNT()", 0) > 0;
}

void DbWriter::CloseSimulation(const Record& record) {
  SimInfo* sim = FindSimulation(record.simulation_id);
  if (sim == nullptr) return;
  const EndedPayload ended = ReadEnded(record);
  const std::string sid = std::to_string(sim->id);
  const std::string reason =
      ended.reason.empty() ? std::string("the sim stopped") : ColumnText(ended.reason, 255);
  const std::string logged = "(SELECT MAX(step) FROM SimulationRow WHERE simulationID = " + sid + ")";
  // A sim that went silent ends at the last step seen (a step refused
  // after it was received is in LogGap, not in SimulationRow).
  const std::string last_step =
      ended.kind == EndKind::kSilent
          ? "GREATEST(COALESCE(" + logged + ", -1), " + std::to_string(ended.last_step) + ")"
          : logged;
  db_->Execute("UPDATE Simulation SET endTime = UTC_TIMESTAMP(6), endReason = " + Quoted(reason) +
                   ", lastStep = " + last_step + " WHERE simulationID = " + sid +
                   " AND endTime IS NULL",
               "UPDATE Simulation (close " + sid + ")");
  if (db_->QueryInt("SELECT ROW_COUNT()", "SELECT ROW_COUNT()", 0) == 0) return;  // closed before
  notice_("closed simulation " + sid + ": " + reason +
          (ended.kind == EndKind::kStopped
               ? " at step " + std::to_string(ended.last_step)
               : std::string()));
}

void DbWriter::ReopenSimulation(const Record& record) {
  SimInfo* sim = FindSimulation(record.simulation_id);
  if (sim == nullptr) return;
  const std::string sid = std::to_string(sim->id);
  // Open again as if it had never closed: a reader takes endTime NULL as
  // running; lastStep is set again when it closes.
  db_->Execute("UPDATE Simulation SET endTime = NULL, endReason = NULL, lastStep = NULL"
               " WHERE simulationID = " + sid + " AND endTime IS NOT NULL",
               "UPDATE Simulation (reopen " + sid + ")");
  if (db_->QueryInt("SELECT ROW_COUNT()", "SELECT ROW_COUNT()", 0) == 0) return;  // open already
  notice_("reopened simulation " + sid + ": " + ReadReopened(record));
}

struct DbWriter::RunRecords {
  std::map<int64_t, std::vector<RunItem>> steps;  // states and gaps by bus simulation id
  std::vector<const Record*> events;              // sensor readings, commands, replies
  uint64_t undecodable = 0;
};

DbWriter::RunRecords DbWriter::SortRun(const std::vector<const Record*>& run, WriteResult* result) {
  RunRecords sorted;
  for (const Record* r : run) {
    if (FindSimulation(r->simulation_id) == nullptr) {
      ++result->unwritable;
      notice_(std::string("a ") + RecordKindName(r->kind) + " of bus simulation " +
              std::to_string(r->simulation_id) +
              " has no Simulation row (its SIM_MODEL never reached the database); not written");
      continue;
    }
    if (r->kind == RecordKind::kState) {
      RunItem item;
      if (!DecodeRecord(*r, &item.state, notice_)) {
        ++sorted.undecodable;
        continue;
      }
      sorted.steps[r->simulation_id].push_back(std::move(item));
    } else if (r->kind == RecordKind::kGap) {
      RunItem item;
      item.is_gap = true;
      item.gap = ReadGap(*r);
      sorted.steps[r->simulation_id].push_back(std::move(item));
    } else {
      sorted.events.push_back(r);
    }
  }
  return sorted;
}

void DbWriter::WriteRun(const std::vector<const Record*>& run, bool check_present,
                        bool force_insert, WriteResult* result) {
  const RunRecords sorted = SortRun(run, result);
  if (sorted.steps.empty() && sorted.events.empty()) return;

  db_->Begin();
  std::vector<int64_t> published;  // publish times of the states written
  std::map<int64_t, int64_t> new_last_step;
  WriteResult pending;
  pending.unwritable = sorted.undecodable;
  for (const auto& [bus_id, items] : sorted.steps)
    new_last_step[bus_id] =
        WriteSteps(*FindSimulation(bus_id), items, check_present, force_insert, &pending, &published);
  EventRows events(db_.get());
  for (const Record* r : sorted.events) {
    const SimInfo* sim = FindSimulation(r->simulation_id);
    events.Add(*r, sim->id, sim->sensor_ids, notice_);
  }
  pending.rows_written += events.Finish();
  db_->Commit();
  for (const auto& [bus_id, last] : new_last_step) simulations_[bus_id].last_step = last;
  AddCommitted(pending, published, result);
}

int64_t DbWriter::WriteSteps(const SimInfo& sim, const std::vector<RunItem>& items,
                             bool check_present, bool force_insert, WriteResult* pending,
                             std::vector<int64_t>* published) {
  const StepSpan span = SpanOf(items);
  StepPresence presence;
  if (span.any_state && (check_present || span.lo <= sim.last_step))
    presence = ReadPresence(db_.get(), sim.id, span);
  const StepPlan plan = PlanSteps(items, sim.last_step, sim.stride, presence);
  pending->rows_written += InsertGaps(db_.get(), sim.id, plan.gaps);
  pending->gaps += plan.gaps.size();
  for (const GapRow& gap : plan.gaps) pending->missing_steps += static_cast<uint64_t>(gap.missing);
  pending->states_present += plan.states_present;
  if (plan.fresh.empty() && plan.repaired.empty()) return plan.last_step;

  std::unordered_map<int64_t, int64_t> row_ids = presence.incomplete;
  uint64_t rows = 0;
  if (!plan.fresh.empty()) {
    rows += InsertSimulationRows(db_.get(), sim.id, span, plan.fresh, &row_ids);
    const InsertMethod method =
        force_insert ? InsertMethod::kMultiRowInsert : MethodFor(plan.fresh.size());
    rows += InsertStateRows(db_.get(), plan.fresh,
                            {row_ids, sim.body_ids, sim.joint_ids, method, options_.scratch_dir, false});
  }
  if (!plan.repaired.empty()) {
    rows += InsertStateRows(db_.get(), plan.repaired,
                            {row_ids, sim.body_ids, sim.joint_ids, InsertMethod::kMultiRowInsert,
                             options_.scratch_dir, true});
    pending->states_repaired += plan.repaired.size();
  }
  for (const auto* list : {&plan.fresh, &plan.repaired})
    for (const state_t* s : *list) published->push_back(s->utime);
  pending->states_written += plan.fresh.size() + plan.repaired.size();
  pending->rows_written += rows;
  return plan.last_step;
}

}  // namespace simpartner::logger
