#include "simpartner/logger/spool.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace simpartner::logger {
namespace {

constexpr uint32_t kMagic = 0x31525053;  // "SPR1" little-endian
constexpr size_t kHeaderBytes = 32;
constexpr uint32_t kMaxPayload = 512u << 20;
constexpr size_t kReadAhead = 1 << 20;
constexpr uint64_t kFirstSeq = 1000000000000ull;  // leaves room for front segments

std::string Errno() { return std::strerror(errno); }

bool AllDigits(const std::string& s, size_t count) {
  return std::all_of(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(count),
                     [](unsigned char c) { return std::isdigit(c) != 0; });
}

void PutU32(uint8_t* out, uint32_t v) { std::memcpy(out, &v, 4); }
void PutI64(uint8_t* out, int64_t v) { std::memcpy(out, &v, 8); }
uint32_t GetU32(const uint8_t* in) {
  uint32_t v;
  std::memcpy(&v, in, 4);
  return v;
}
int64_t GetI64(const uint8_t* in) {
  int64_t v;
  std::memcpy(&v, in, 8);
  return v;
}

// CRC of the header fields after the magic (kind, length, simulation id,
// receive time) and of the payload.
uint32_t FrameCrc(const uint8_t* header, const uint8_t* payload, size_t payload_size) {
  uint32_t crc = Crc32(header + 4, 8);
  crc = Crc32(header + 16, 16, crc);
  return Crc32(payload, payload_size, crc);
}

void WriteAll(int fd, const uint8_t* data, size_t size, uint64_t offset, const std::string& path) {
  while (size > 0) {
    const ssize_t n = ::pwrite(fd, data, size, static_cast<off_t>(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw SpoolError("cannot write spool file " + path + ": " + Errno());
    }
    data += n;
    size -= static_cast<size_t>(n);
    offset += static_cast<uint64_t>(n);
  }
}

}  // namespace

uint32_t Crc32(const uint8_t* data, size_t size, uint32_t crc) {
  static const std::array<uint32_t, 256> kTable = [] {
    std::array<uint32_t, 256> table{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      table[i] = c;
    }
    return table;
  }();
  crc = ~crc;
  for (size_t i = 0; i < size; ++i) crc = kTable[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

std::vector<uint8_t> FrameRecord(const Record& record) {
  std::vector<uint8_t> frame(kHeaderBytes + record.payload.size());
  uint8_t* h = frame.data();
  PutU32(h, kMagic);
  h[4] = static_cast<uint8_t>(record.kind);
  PutU32(h + 8, static_cast<uint32_t>(record.payload.size()));
  PutI64(h + 16, record.simulation_id);
  PutI64(h + 24, record.received_us);
  if (!record.payload.empty())
    std::memcpy(h + kHeaderBytes, record.payload.data(), record.payload.size());
  PutU32(h + 12, FrameCrc(h, h + kHeaderBytes, record.payload.size()));
  return frame;
}

std::string Spool::SegmentPath(uint64_t seq) const {
  char name[32];
  std::snprintf(name, sizeof name, "%020llu.seg", static_cast<unsigned long long>(seq));
  return dir_ + "/" + name;
}

std::string Spool::DonePath(uint64_t seq) const {
  char name[32];
  std::snprintf(name, sizeof name, "%020llu.done", static_cast<unsigned long long>(seq));
  return dir_ + "/" + name;
}

Spool::Spool(std::string dir, uint64_t segment_bytes, Notice notice)
    : dir_(std::move(dir)), segment_bytes_(segment_bytes), notice_(std::move(notice)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw SpoolError("cannot create spool directory " + dir_ + ": " + ec.message());
  const std::string lock_path = dir_ + "/lock";
  lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (lock_fd_ < 0) throw SpoolError("cannot open " + lock_path + ": " + Errno());
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    char owner[32] = {0};
    const ssize_t n = ::pread(lock_fd_, owner, sizeof owner - 1, 0);
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw SpoolError("spool directory " + dir_ + " is in use by another simpartner-logger" +
                     (n > 0 ? " (pid " + std::string(owner, static_cast<size_t>(n)) + ")" : ""));
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(lock_fd_, 0) == 0) WriteAll(lock_fd_, reinterpret_cast<const uint8_t*>(pid.data()), pid.size(), 0, lock_path);

  // Segments and their commit marks.
  std::vector<uint64_t> seqs;
  for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    if (name.size() == 24 && name.compare(20, 4, ".seg") == 0 &&
        AllDigits(name, 20)) {
      seqs.push_back(std::stoull(name.substr(0, 20)));
    }
  }
  std::sort(seqs.begin(), seqs.end());
  for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
    // A commit mark whose segment is gone (deleted just before a crash).
    const std::string name = entry.path().filename().string();
    if (name.size() == 25 && name.compare(20, 5, ".done") == 0 &&
        AllDigits(name, 20) &&
        !std::binary_search(seqs.begin(), seqs.end(), std::stoull(name.substr(0, 20)))) {
      std::filesystem::remove(entry.path(), ec);
    }
  }
  for (uint64_t seq : seqs) {
    Segment s;
    s.seq = seq;
    const std::string path = SegmentPath(seq);
    s.fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (s.fd < 0) throw SpoolError("cannot open spool file " + path + ": " + Errno());
    struct stat st {};
    if (::fstat(s.fd, &st) != 0) throw SpoolError("cannot stat spool file " + path + ": " + Errno());
    s.size = static_cast<uint64_t>(st.st_size);
    const std::string done_path = DonePath(seq);
    const int done_fd = ::open(done_path.c_str(), O_RDONLY | O_CLOEXEC);
    if (done_fd >= 0) {
      uint8_t mark[16];
      if (::pread(done_fd, mark, 16, 0) == 16) {
        const uint64_t committed = static_cast<uint64_t>(GetI64(mark));
        const uint64_t check = static_cast<uint64_t>(GetI64(mark + 8));
        if (check == ~committed && committed <= s.size) s.committed = committed;
      }
      ::close(done_fd);
    }
    segments_.push_back(s);
  }
  if (!segments_.empty()) {
    // Only the last segment can end in an append cut short.
    Segment& last = segments_.back();
    const uint64_t valid = ScanValidEnd(last, last.committed);
    if (valid < last.size) {
      notice_("spool " + SegmentPath(last.seq) + ": cut off a damaged tail of " +
              std::to_string(last.size - valid) + " bytes (an append interrupted by a crash)");
      if (::ftruncate(last.fd, static_cast<off_t>(valid)) != 0)
        throw SpoolError("cannot truncate spool file " + SegmentPath(last.seq) + ": " + Errno());
      last.size = valid;
      buffer_.clear();  // it holds the cut-off bytes, which appends will overwrite
      buffer_seq_ = 0;
    }
    next_seq_ = last.seq + 1;
    read_seq_ = segments_.front().seq;
    read_offset_ = segments_.front().committed;
  } else {
    next_seq_ = kFirstSeq;
  }
}

Spool::~Spool() {
  for (Segment& s : segments_) ::close(s.fd);
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

Spool::Segment* Spool::Find(uint64_t seq) {
  for (Segment& s : segments_)
    if (s.seq == seq) return &s;
  return nullptr;
}

Spool::Segment& Spool::AppendSegment() {
  if (segments_.empty() || segments_.back().size >= segment_bytes_) {
    Segment s;
    s.seq = next_seq_++;
    const std::string path = SegmentPath(s.seq);
    s.fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (s.fd < 0) throw SpoolError("cannot create spool file " + path + ": " + Errno());
    if (segments_.empty()) {
      read_seq_ = s.seq;
      read_offset_ = 0;
    }
    segments_.push_back(s);
  }
  return segments_.back();
}

void Spool::Append(const Record& record) {
  const std::vector<uint8_t> frame = FrameRecord(record);
  std::lock_guard<std::mutex> lock(mutex_);
  Segment& s = AppendSegment();
  try {
    WriteAll(s.fd, frame.data(), frame.size(), s.size, SegmentPath(s.seq));
  } catch (const SpoolError&) {
    // Leave no partial frame behind.
    if (::ftruncate(s.fd, static_cast<off_t>(s.size)) != 0)
      notice_("cannot cut a partial record off " + SegmentPath(s.seq) + ": " + Errno() +
              "; the next start cuts it off");
    if (buffer_seq_ == s.seq) {
      buffer_.clear();
      buffer_seq_ = 0;
    }
    throw;
  }
  s.size += frame.size();
}

bool Spool::ReadRecordAt(const Segment& segment, uint64_t offset, Record* record, uint64_t* end,
                         std::string* problem) {
  auto ensure = [&](uint64_t from, uint64_t bytes) -> const uint8_t* {
    if (from + bytes > segment.size) return nullptr;
    if (buffer_seq_ != segment.seq || from < buffer_start_ ||
        from + bytes > buffer_start_ + buffer_.size()) {
      const uint64_t want = std::min<uint64_t>(std::max<uint64_t>(kReadAhead, bytes),
                                               segment.size - from);
      buffer_.resize(want);
      size_t got = 0;
      while (got < want) {
        const ssize_t n = ::pread(segment.fd, buffer_.data() + got, want - got,
                                  static_cast<off_t>(from + got));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw SpoolError("cannot read spool file " + SegmentPath(segment.seq) + ": " + Errno());
        if (n == 0) break;
        got += static_cast<size_t>(n);
      }
      buffer_.resize(got);
      buffer_seq_ = segment.seq;
      buffer_start_ = from;
      if (got < bytes) return nullptr;
    }
    return buffer_.data() + (from - buffer_start_);
  };
  const uint8_t* h = ensure(offset, kHeaderBytes);
  if (h == nullptr) {
    *problem = "record header cut short";
    return false;
  }
  if (GetU32(h) != kMagic) {
    *problem = "no record frame";
    return false;
  }
  const uint8_t kind = h[4];
  const uint32_t length = GetU32(h + 8);
  if (!IsKnownRecordKind(kind) || length > kMaxPayload) {
    *problem = "bad record header (kind " + std::to_string(kind) + ", length " +
               std::to_string(length) + ")";
    return false;
  }
  uint8_t header[kHeaderBytes];
  std::memcpy(header, h, kHeaderBytes);
  const uint8_t* payload = ensure(offset + kHeaderBytes, length);
  if (payload == nullptr && length > 0) {
    *problem = "record of " + std::to_string(length) + " bytes cut short";
    return false;
  }
  if (FrameCrc(header, payload, length) != GetU32(header + 12)) {
    *problem = "checksum mismatch";
    return false;
  }
  if (record != nullptr) {
    record->kind = static_cast<RecordKind>(kind);
    record->simulation_id = GetI64(header + 16);
    record->received_us = GetI64(header + 24);
    record->payload.assign(payload, payload + length);
  }
  *end = offset + kHeaderBytes + length;
  return true;
}

uint64_t Spool::ScanValidEnd(const Segment& segment, uint64_t from) {
  uint64_t offset = from;
  std::string problem;
  while (offset < segment.size) {
    uint64_t end = 0;
    if (!ReadRecordAt(segment, offset, nullptr, &end, &problem)) break;
    offset = end;
  }
  return offset;
}

std::optional<Spool::Entry> Spool::ReadNext() {
  std::lock_guard<std::mutex> lock(mutex_);
  while (true) {
    auto it = std::find_if(segments_.begin(), segments_.end(),
                           [this](const Segment& s) { return s.seq >= read_seq_; });
    if (it == segments_.end()) return std::nullopt;
    if (it->seq != read_seq_) {
      read_seq_ = it->seq;
      read_offset_ = it->committed;
    }
    if (read_offset_ >= it->size) {
      if (std::next(it) == segments_.end()) return std::nullopt;  // the append segment
      read_seq_ = std::next(it)->seq;
      read_offset_ = std::next(it)->committed;
      continue;
    }
    Entry entry;
    uint64_t end = 0;
    std::string problem;
    if (!ReadRecordAt(*it, read_offset_, &entry.record, &end, &problem)) {
      ++damaged_;
      notice_("spool " + SegmentPath(it->seq) + ": damaged record at offset " +
              std::to_string(read_offset_) + " (" + problem + "); skipping the remaining " +
              std::to_string(it->size - read_offset_) + " bytes of this segment");
      read_offset_ = it->size;
      continue;
    }
    read_offset_ = end;
    entry.end = Position{it->seq, end};
    return entry;
  }
}

void Spool::WriteDone(const Segment& segment) {
  uint8_t mark[16];
  PutI64(mark, static_cast<int64_t>(segment.committed));
  PutI64(mark + 8, static_cast<int64_t>(~segment.committed));
  const std::string path = DonePath(segment.seq);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) throw SpoolError("cannot write spool file " + path + ": " + Errno());
  try {
    WriteAll(fd, mark, sizeof mark, 0, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

void Spool::Remove(uint64_t seq) {
  auto it = std::find_if(segments_.begin(), segments_.end(),
                         [seq](const Segment& s) { return s.seq == seq; });
  if (it == segments_.end()) return;
  ::close(it->fd);
  // Segment first: a commit mark without its segment is ignored at start.
  ::unlink(SegmentPath(seq).c_str());
  ::unlink(DonePath(seq).c_str());
  if (buffer_seq_ == seq) {
    buffer_.clear();
    buffer_seq_ = 0;
  }
  segments_.erase(it);
}

void Spool::Commit(Position end) {
  std::lock_guard<std::mutex> lock(mutex_);
  Segment* segment = Find(end.segment);
  if (segment == nullptr) return;  // already removed
  // Reading is in order: every segment before this one that the reader has
  // left is done. (A front segment written by Prepend is still to be read.)
  while (!segments_.empty() && segments_.front().seq < end.segment &&
         segments_.front().seq < read_seq_)
    Remove(segments_.front().seq);
  segment = Find(end.segment);
  segment->committed = std::max(segment->committed, end.offset);
  const bool finished = segment->committed >= segment->size;
  const bool reader_past = read_seq_ > segment->seq ||
                           (read_seq_ == segment->seq && read_offset_ >= segment->size);
  if (finished && reader_past) {
    Remove(segment->seq);
    if (segments_.empty()) read_offset_ = 0;
  } else {
    // The mark only saves a restart from replaying committed records (which
    // the writer skips): a full disk must not stop the commit, or the
    // segment would never be freed.
    try {
      WriteDone(*segment);
      done_mark_failing_ = false;
    } catch (const SpoolError& e) {
      if (!done_mark_failing_)
        notice_(std::string(e.what()) + "; until it can be written, a restart would write up to " +
                std::to_string(segment->committed) +
                " committed bytes of this segment again (skipped as already there)");
      done_mark_failing_ = true;
    }
  }
}

void Spool::Prepend(const std::vector<Record>& records) {
  if (records.empty()) return;
  std::lock_guard<std::mutex> lock(mutex_);
  Segment s;
  s.seq = segments_.empty() ? next_seq_++ : segments_.front().seq - 1;
  const std::string path = SegmentPath(s.seq);
  s.fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (s.fd < 0) throw SpoolError("cannot create spool file " + path + ": " + Errno());
  std::vector<uint8_t> data;
  for (const Record& r : records) {
    const std::vector<uint8_t> frame = FrameRecord(r);
    data.insert(data.end(), frame.begin(), frame.end());
  }
  try {
    WriteAll(s.fd, data.data(), data.size(), 0, path);
    if (::fsync(s.fd) != 0) throw SpoolError("cannot sync spool file " + path + ": " + Errno());
  } catch (...) {
    ::close(s.fd);
    ::unlink(path.c_str());
    throw;
  }
  s.size = data.size();
  segments_.push_front(s);
  read_seq_ = s.seq;
  read_offset_ = 0;
}

uint64_t Spool::UnreadBytesLocked() const {
  uint64_t bytes = 0;
  for (const Segment& s : segments_) {
    if (s.seq > read_seq_) bytes += s.size - s.committed;
    else if (s.seq == read_seq_ && s.size > read_offset_) bytes += s.size - read_offset_;
  }
  return bytes;
}

bool Spool::HasUnread() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return UnreadBytesLocked() > 0;
}

uint64_t Spool::UnreadBytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return UnreadBytesLocked();
}

uint64_t Spool::StoredBytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  uint64_t bytes = 0;
  for (const Segment& s : segments_) bytes += s.size - s.committed;
  return bytes;
}

uint64_t Spool::damaged_records() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return damaged_;
}

}  // namespace simpartner::logger
