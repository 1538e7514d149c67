#include "simpartner/logger/record_queue.h"

#include <algorithm>

namespace simpartner::logger {

RecordQueue::RecordQueue(uint64_t max_memory_bytes, Spool* spool)
    : max_memory_bytes_(max_memory_bytes), spool_(spool) {
  // Records left from an earlier run come before anything new.
  spilling_ = spool_->HasUnread();
}

void RecordQueue::Push(Record&& record) {
  std::lock_guard<std::mutex> lock(mutex_);
  const uint64_t size = record.ByteSize();
  if (spilling_ || memory_bytes_ + size > max_memory_bytes_) {
    spool_->Append(record);  // under the lock: the writer sees disk and memory in order
    spilling_ = true;
    ++spilled_;
  } else {
    memory_bytes_ += size;
    peak_memory_bytes_ = std::max(peak_memory_bytes_, memory_bytes_);
    memory_.push_back(std::move(record));
  }
  ready_.notify_one();
}

Batch RecordQueue::Take(size_t max_records, uint64_t max_bytes, std::chrono::milliseconds wait,
                        size_t min_records, std::chrono::milliseconds linger) {
  Batch batch;
  uint64_t bytes = 0;
  bool read_disk = false;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait_for(lock, wait, [this] {
      return woken_ || !memory_.empty() || (spilling_ && spool_->HasUnread());
    });
    if (!woken_ && !spilling_ && !memory_.empty() && memory_.size() < min_records) {
      ready_.wait_for(lock, linger, [this, min_records] {
        return woken_ || spilling_ || memory_.size() >= min_records;
      });
    }
    woken_ = false;
    while (!memory_.empty() && batch.records.size() < max_records && bytes < max_bytes) {
      const uint64_t size = memory_.front().ByteSize();
      bytes += size;
      memory_bytes_ -= size;
      batch.records.push_back(std::move(memory_.front()));
      memory_.pop_front();
    }
    // Disk only after memory: while spilling, memory holds the older records.
    read_disk = memory_.empty() && spilling_;
  }
  if (read_disk) {
    // Outside the lock, so that Push goes on appending meanwhile.
    while (batch.records.size() < max_records && bytes < max_bytes) {
      std::optional<Spool::Entry> entry = spool_->ReadNext();
      if (!entry) break;
      bytes += entry->record.ByteSize();
      batch.spool_end = entry->end;
      batch.records.push_back(std::move(entry->record));
    }
    std::lock_guard<std::mutex> lock(mutex_);
    // Caught up with the disk: new records may use memory again. Checked
    // under the lock, so no Push can slip a record onto disk unseen.
    if (memory_.empty() && spilling_ && !spool_->HasUnread()) spilling_ = false;
  }
  return batch;
}

void RecordQueue::Commit(const Batch& batch) {
  if (batch.spool_end) spool_->Commit(*batch.spool_end);
}

bool RecordQueue::Drained() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return memory_.empty() && !spool_->HasUnread();
}

size_t RecordQueue::SaveUnwritten(const Batch& unwritten) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Record> records = unwritten.records;
  for (Record& r : memory_) records.push_back(std::move(r));
  memory_.clear();
  memory_bytes_ = 0;
  // The records of `unwritten` that came from disk now also live in the new
  // front segment (written and synced first); mark the old copies done.
  spool_->Prepend(records);
  if (unwritten.spool_end) spool_->Commit(*unwritten.spool_end);
  spilling_ = spool_->HasUnread();
  return records.size();
}

void RecordQueue::Wake() {
  std::lock_guard<std::mutex> lock(mutex_);
  woken_ = true;
  ready_.notify_all();
}

QueueStats RecordQueue::Stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  QueueStats s;
  s.memory_records = memory_.size();
  s.memory_bytes = memory_bytes_;
  s.peak_memory_bytes = peak_memory_bytes_;
  s.spilled_records = spilled_;
  s.spool_unread_bytes = spool_->UnreadBytes();
  s.spool_stored_bytes = spool_->StoredBytes();
  s.spilling = spilling_;
  return s;
}

}  // namespace simpartner::logger
