// The logger's spill file on disk: records the memory queue had no room for
// (the database is slow or away) wait here in arrival order until the writer
// catches up, and survive a restart of the logger. Nothing is dropped: a
// record leaves the spool only once the writer says it is in the database.
//
// Layout: DIR/<20-digit sequence>.seg files of framed records (magic, kind,
// length, CRC-32, simulation id, receive time, payload), read in sequence
// order; DIR/<sequence>.done holds how far a segment is committed; DIR/lock
// keeps a second logger out. Appends go to the last segment, a new one after
// segment_bytes; fully committed segments are deleted. At shutdown, records
// the writer still holds go into a new segment in front of all others so the
// order is kept.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/logger/record.h"

namespace simpartner::logger {

// The spool directory or one of its files cannot be used (path and cause).
class SpoolError : public Error {
 public:
  using Error::Error;
};

class Spool {
 public:
  // Where a read record ends: commit up to here.
  struct Position {
    uint64_t segment = 0;
    uint64_t offset = 0;
  };
  struct Entry {
    Record record;
    Position end;
  };
  using Notice = std::function<void(const std::string&)>;

  // Opens (creating) dir and locks it. A damaged tail of the last segment
  // (an append cut short by a crash) is cut off and reported through notice.
  // Throws SpoolError.
  Spool(std::string dir, uint64_t segment_bytes, Notice notice);
  Spool(const Spool&) = delete;
  Spool& operator=(const Spool&) = delete;
  ~Spool();

  // Throws SpoolError (e.g. the disk is full); the spool is unchanged then.
  void Append(const Record& record);
  // Next record after the read position, or nullopt when all are read. A
  // damaged record (bad frame or checksum) is reported and the rest of its
  // segment skipped. Throws SpoolError on I/O errors.
  std::optional<Entry> ReadNext();
  // Every record read up to `end` is in the database.
  void Commit(Position end);
  // Writes records as a new first segment (synced to disk) and moves the
  // read position to its start.
  void Prepend(const std::vector<Record>& records);

  bool HasUnread() const;
  uint64_t UnreadBytes() const;
  // Bytes of records not yet committed (what a restart would replay).
  uint64_t StoredBytes() const;
  uint64_t damaged_records() const;
  const std::string& dir() const { return dir_; }

 private:
  struct Segment {
    uint64_t seq = 0;
    uint64_t size = 0;       // valid bytes
    uint64_t committed = 0;  // bytes known to be in the database
    int fd = -1;
  };
  std::string SegmentPath(uint64_t seq) const;
  std::string DonePath(uint64_t seq) const;
  Segment* Find(uint64_t seq);
  Segment& AppendSegment();
  void WriteDone(const Segment& segment);
  void Remove(uint64_t seq);
  // Valid end of the records in [from, size) of a segment.
  uint64_t ScanValidEnd(const Segment& segment, uint64_t from);
  // Reads and checks the record at offset; false if damaged.
  bool ReadRecordAt(const Segment& segment, uint64_t offset, Record* record, uint64_t* end,
                    std::string* problem);
  uint64_t UnreadBytesLocked() const;

  const std::string dir_;
  const uint64_t segment_bytes_;
  Notice notice_;
  int lock_fd_ = -1;
  mutable std::mutex mutex_;
  std::deque<Segment> segments_;  // by increasing seq
  uint64_t next_seq_ = 0;
  uint64_t read_seq_ = 0;
  uint64_t read_offset_ = 0;
  uint64_t damaged_ = 0;
  bool done_mark_failing_ = false;  // a commit mark could not be written (reported once)
  // Read-ahead buffer of one segment.
  std::vector<uint8_t> buffer_;
  uint64_t buffer_seq_ = 0;
  uint64_t buffer_start_ = 0;
};

// Encodes one record as framed in a segment (for tests).
std::vector<uint8_t> FrameRecord(const Record& record);
uint32_t Crc32(const uint8_t* data, size_t size, uint32_t crc = 0);

}  // namespace simpartner::logger
