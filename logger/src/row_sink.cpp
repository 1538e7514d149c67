#include "row_sink.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "simpartner/logger/sql_text.h"

namespace simpartner::logger {
namespace {

constexpr size_t kInsertStatementBytes = 1 << 20;
constexpr size_t kLoadDataFileBytes = 16 << 20;

// Index -> database id, or NULL for -1 (the static world, no robot).
void AppendId(std::string* out, const std::vector<int64_t>& ids, int64_t index) {
  if (index < 0 || index >= static_cast<int64_t>(ids.size())) out->append("NULL");
  else AppendInt(out, ids[static_cast<size_t>(index)]);
}

}  // namespace

RowSink::RowSink(DbConnection* db, InsertMethod method, const std::string& scratch_dir,
                 std::string table, std::string columns, std::string on_duplicate)
    : db_(db),
      load_data_(method == InsertMethod::kLoadDataLocal),
      scratch_path_(scratch_dir + "/loaddata-" + table + ".tsv"),
      table_(std::move(table)),
      columns_(std::move(columns)),
      on_duplicate_(std::move(on_duplicate)) {
  buffer_.reserve(load_data_ ? kLoadDataFileBytes + 65536 : kInsertStatementBytes + 65536);
  Start();
}

void RowSink::BeginRow() {
  if (!load_data_) {
    if (rows_in_buffer_ > 0) buffer_.push_back(',');
    buffer_.push_back('(');
  }
  first_field_ = true;
}

void RowSink::Double(double v) {
  Separator();
  if (load_data_ && !std::isfinite(v)) buffer_.append("\\N");
  else AppendDouble(&buffer_, v);
}

void RowSink::Int(int64_t v) {
  Separator();
  AppendInt(&buffer_, v);
}

void RowSink::Id(const std::vector<int64_t>& ids, int64_t index) {
  Separator();
  if (load_data_ && (index < 0 || index >= static_cast<int64_t>(ids.size()))) buffer_.append("\\N");
  else AppendId(&buffer_, ids, index);
}

void RowSink::Text(std::string_view text) {
  Separator();
  if (load_data_) AppendTsvField(&buffer_, text);
  else AppendQuoted(&buffer_, text);
}

void RowSink::Expression(const std::string& sql) {
  Separator();
  buffer_.append(sql);
}

void RowSink::EndRow() {
  buffer_.push_back(load_data_ ? '\n' : ')');
  ++rows_in_buffer_;
  ++rows_;
  if (buffer_.size() >= (load_data_ ? kLoadDataFileBytes : kInsertStatementBytes)) Flush();
}

void RowSink::Start() {
  buffer_.clear();
  rows_in_buffer_ = 0;
  if (!load_data_) buffer_ = "INSERT INTO " + table_ + " (" + columns_ + ") VALUES ";
}

void RowSink::Separator() {
  if (!first_field_) buffer_.push_back(load_data_ ? '\t' : ',');
  first_field_ = false;
}

void RowSink::Flush() {
  if (rows_in_buffer_ == 0) return;
  const std::string what = (load_data_ ? "LOAD DATA LOCAL INTO " : "INSERT INTO ") + table_ +
                           " (" + std::to_string(rows_in_buffer_) + " rows)";
  if (load_data_) {
    // Numbers only (the per-step tables have no text): read as bytes.
    WriteFile(what);
    // The file goes as soon as the server has read it: nothing stays in
    // the spool directory, and its space is free for the spool.
    struct RemoveFile {
      const std::string& path;
      ~RemoveFile() { ::unlink(path.c_str()); }
    } remove{scratch_path_};
    db_->Execute("LOAD DATA LOCAL INFILE " + Quoted(scratch_path_) + " INTO TABLE " + table_ +
                     " CHARACTER SET binary FIELDS TERMINATED BY '\\t' LINES TERMINATED BY "
                     "'\\n' (" + columns_ + ")",
                 what);
  } else {
    if (!on_duplicate_.empty()) buffer_ += " ON DUPLICATE KEY UPDATE " + on_duplicate_;
    db_->Execute(buffer_, what);
  }
  Start();
}

void RowSink::WriteFile(const std::string& what) {
  const int fd = ::open(scratch_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0)
    throw ScratchFileError(what + ": cannot write " + scratch_path_ + ": " + std::strerror(errno));
  auto fail = [&](const std::string& cause) {
    ::unlink(scratch_path_.c_str());
    throw ScratchFileError(what + ": cannot write " + scratch_path_ + ": " + cause);
  };
  size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n = ::write(fd, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string cause = std::strerror(errno);
      ::close(fd);
      fail(cause);
    }
    done += static_cast<size_t>(n);
  }
  if (::close(fd) != 0) fail(std::strerror(errno));
}

}  // namespace simpartner::logger
