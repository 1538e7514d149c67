// Between the receive thread and the database writer: a bounded queue in
// memory that spills to the spool on disk when it is full. Push never waits
// for the writer and never drops a record; the order of records is kept
// across memory and disk (once spilling starts, records go to disk until
// the writer has caught up with everything there).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <vector>

#include "simpartner/logger/record.h"
#include "simpartner/logger/spool.h"

namespace simpartner::logger {

// Records handed to the writer, oldest first.
struct Batch {
  std::vector<Record> records;
  std::optional<Spool::Position> spool_end;  // end of the last record taken from disk
  bool empty() const { return records.empty(); }
};

struct QueueStats {
  uint64_t memory_records = 0;
  uint64_t memory_bytes = 0;
  uint64_t peak_memory_bytes = 0;
  uint64_t spilled_records = 0;  // pushed to disk since start
  uint64_t spool_unread_bytes = 0;
  uint64_t spool_stored_bytes = 0;
  bool spilling = false;
};

class RecordQueue {
 public:
  // spool outlives the queue.
  RecordQueue(uint64_t max_memory_bytes, Spool* spool);

  // Never blocks on the writer. Throws SpoolError if the record has to go to
  // disk and cannot (e.g. the disk is full); `record` is then left as it
  // was (moved from only when taken).
  void Push(Record&& record);
  // Oldest records first, up to the limits; waits up to `wait` for the
  // first, then up to `linger` for at least `min_records` (bigger batches
  // cost the database less per row, for a few milliseconds of lag).
  Batch Take(size_t max_records, uint64_t max_bytes, std::chrono::milliseconds wait,
             size_t min_records = 1, std::chrono::milliseconds linger = std::chrono::milliseconds(0));
  // The batch is in the database.
  void Commit(const Batch& batch);
  // Nothing left in memory or unread on disk.
  bool Drained() const;
  // At shutdown: `unwritten` (a batch the writer could not write) and what
  // is still in memory go to the front of the spool, in order, so that the
  // next run writes them first. Returns how many records that was.
  size_t SaveUnwritten(const Batch& unwritten);
  // Makes a waiting Take return.
  void Wake();
  QueueStats Stats() const;

 private:
  const uint64_t max_memory_bytes_;
  Spool* spool_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Record> memory_;
  uint64_t memory_bytes_ = 0;
  uint64_t peak_memory_bytes_ = 0;
  uint64_t spilled_ = 0;
  bool spilling_ = false;
  bool woken_ = false;
};

}  // namespace simpartner::logger
