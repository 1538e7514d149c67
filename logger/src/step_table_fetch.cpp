#include "step_table_fetch.h"

#include <cppconn/exception.h>
#include <cppconn/resultset_metadata.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "simpartner/logger/sql_text.h"

namespace simpartner::logger {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Rows per chunk: big enough that a statement's fixed cost is small, small
// enough that the two connections take turns often (and that a chunk's
// result, stored whole by the client library, stays a few MB).
constexpr size_t kRowsPerChunk = 100000;

std::string Condition(const std::string& text, double value) {
  std::string out = text;
  AppendDouble(&out, value);
  return out;
}

// One statement's worth: the steps [first, last] (indices) of one table.
struct Chunk {
  StepTableFetch* fetch;
  size_t first, last;
};

std::vector<Chunk> Chunks(const StepIndex& steps, std::vector<StepTableFetch>* fetches) {
  std::vector<Chunk> chunks;
  for (StepTableFetch& fetch : *fetches) {
    fetch.arrays.assign(fetch.ids.size(),
                        std::vector<double>(steps.size() * fetch.columns.size(), kNaN));
    if (fetch.ids.empty() || steps.size() == 0) continue;
    const size_t per_chunk = std::max<size_t>(1, kRowsPerChunk / fetch.ids.size());
    for (size_t first = 0; first < steps.size(); first += per_chunk)
      chunks.push_back({&fetch, first, std::min(steps.size(), first + per_chunk) - 1});
  }
  return chunks;
}

std::string ChunkSql(const Chunk& chunk, uint32_t simulation, const StepIndex& steps) {
  const StepTableFetch& f = *chunk.fetch;
  std::string sql = "SELECT p.simulationRowID, p." + f.id_column;
  for (const std::string& c : f.columns) sql += ", p." + c;
  sql += " FROM SimulationRow r JOIN " + f.table +
         " p ON p.simulationRowID = r.simulationRowID WHERE r.simulationID = " +
         std::to_string(simulation) + " AND r.step BETWEEN " +
         std::to_string(steps.step()[chunk.first]) + " AND " +
         std::to_string(steps.step()[chunk.last]);
  if (!f.every_part) {
    sql += " AND p." + f.id_column + " IN (";
    for (size_t i = 0; i < f.ids.size(); ++i) sql += (i ? "," : "") + std::to_string(f.ids[i]);
    sql += ")";
  }
  return sql;
}

// The index in fetch.ids of each id (ids of one simulation are few).
int64_t PartIndex(const StepTableFetch& fetch, uint64_t id) {
  for (size_t i = 0; i < fetch.ids.size(); ++i)
    if (static_cast<uint64_t>(fetch.ids[i]) == id) return static_cast<int64_t>(i);
  return -1;
}

void FetchChunk(DbConnection* db, uint32_t simulation, const StepIndex& steps, const Chunk& chunk) {
  StepTableFetch& f = *chunk.fetch;
  const std::string what = "read " + f.table + " of steps " +
                           std::to_string(steps.step()[chunk.first]) + " to " +
                           std::to_string(steps.step()[chunk.last]);
  std::unique_ptr<sql::ResultSet> rows = db->QueryBinary(ChunkSql(chunk, simulation, steps), what);
  const size_t columns = f.columns.size();
  try {
    // Most columns are NOT NULL: asking each value whether it was NULL
    // would cost a fifth of the client's time.
    std::vector<bool> nullable(columns);
    for (size_t k = 0; k < columns; ++k)
      nullable[k] = rows->getMetaData()->isNullable(static_cast<uint32_t>(k + 3)) !=
                    sql::ResultSetMetaData::columnNoNulls;
    while (rows->next()) {
      const int64_t index = steps.IndexOf(rows->getUInt64(1));
      const int64_t part = PartIndex(f, rows->getUInt64(2));
      if (index < 0 || part < 0) continue;  // a step outside the range read
      double* out = &f.arrays[static_cast<size_t>(part)][static_cast<size_t>(index) * columns];
      for (size_t k = 0; k < columns; ++k) {
        const double v = static_cast<double>(rows->getDouble(static_cast<uint32_t>(k + 3)));
        out[k] = nullable[k] && rows->wasNull() ? kNaN : v;
      }
    }
  } catch (const sql::SQLException&) {
    db->Rethrow(what);
  }
}

// Takes chunks off a shared counter until none is left or one failed.
class ChunkQueue {
 public:
  explicit ChunkQueue(std::vector<Chunk> chunks) : chunks_(std::move(chunks)) {}
  void Work(DbConnection* db, uint32_t simulation, const StepIndex& steps) {
    try {
      for (size_t i = next_++; i < chunks_.size() && !failed_; i = next_++)
        FetchChunk(db, simulation, steps, chunks_[i]);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      failed_ = true;
    }
  }
  void RethrowFailure() {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::vector<Chunk> chunks_;
  std::atomic<size_t> next_{0};
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::exception_ptr error_;
};

}  // namespace

StepIndex StepIndex::Read(DbConnection* db, uint32_t simulation, double from, double to) {
  std::string sql =
      "SELECT simulationRowID, step, simulationTime FROM SimulationRow WHERE "
      "simulationID = " +
      std::to_string(simulation);
  if (std::isfinite(from)) sql += Condition(" AND simulationTime >= ", from);
  if (std::isfinite(to)) sql += Condition(" AND simulationTime <= ", to);
  std::unique_ptr<sql::ResultSet> rows =
      db->QueryBinary(sql + " ORDER BY step", "read SimulationRow");
  StepIndex index;
  std::vector<uint64_t> row_ids;
  try {
    while (rows->next()) {
      row_ids.push_back(rows->getUInt64(1));
      index.step_.push_back(rows->getInt64(2));
      index.time_.push_back(static_cast<double>(rows->getDouble(3)));
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read SimulationRow");
  }
  index.BuildLookup(row_ids);
  return index;
}

void StepIndex::BuildLookup(const std::vector<uint64_t>& row_ids) {
  if (row_ids.empty()) return;
  const auto [lo, hi] = std::minmax_element(row_ids.begin(), row_ids.end());
  const uint64_t span = *hi - *lo + 1;
  if (span <= 4 * row_ids.size() + 1024) {
    first_row_ = *lo;
    dense_.assign(span, -1);
    for (size_t i = 0; i < row_ids.size(); ++i) dense_[row_ids[i] - *lo] = static_cast<int32_t>(i);
  } else {
    for (size_t i = 0; i < row_ids.size(); ++i) sparse_[row_ids[i]] = static_cast<int64_t>(i);
  }
}

int64_t StepIndex::IndexOf(uint64_t row_id) const {
  if (!dense_.empty())
    return row_id >= first_row_ && row_id - first_row_ < dense_.size() ? dense_[row_id - first_row_]
                                                                       : -1;
  const auto it = sparse_.find(row_id);
  return it == sparse_.end() ? -1 : it->second;
}

void FetchStepTables(DbConnection* db, uint32_t simulation, const StepIndex& steps,
                     std::vector<StepTableFetch>* fetches) {
  std::vector<Chunk> chunks = Chunks(steps, fetches);
  const bool two = chunks.size() > 1;
  ChunkQueue queue(std::move(chunks));
  if (!two) {
    queue.Work(db, simulation, steps);
    return queue.RethrowFailure();
  }
  // The second connection is opened here, so that a server that refuses it
  // fails before any thread starts.
  std::unique_ptr<DbConnection> second = DbConnection::Open(db->target(), false);
  second->UseDatabase(false);
  std::thread helper([&] {
    queue.Work(second.get(), simulation, steps);
    second.reset();
    DbThreadEnd();
  });
  queue.Work(db, simulation, steps);
  helper.join();
  queue.RethrowFailure();
}

}  // namespace simpartner::logger
