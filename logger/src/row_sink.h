// Rows of one table as text, sent as multi-row INSERTs (about 1 MB per
// statement) or LOAD DATA LOCAL files (about 16 MB each): what the writer
// puts every value of a model or a step through.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/logger/db.h"
#include "simpartner/logger/writer.h"

namespace simpartner::logger {

// The LOAD DATA scratch file could not be written (the spool disk full):
// the batch is rolled back and goes again as INSERTs.
class ScratchFileError : public Error {
 public:
  using Error::Error;
};

class RowSink {
 public:
  // method: kMultiRowInsert or kLoadDataLocal (files in scratch_dir).
  // on_duplicate: the INSERT's ON DUPLICATE KEY UPDATE clause, "" for none.
  RowSink(DbConnection* db, InsertMethod method, const std::string& scratch_dir, std::string table,
          std::string columns, std::string on_duplicate = "");

  void BeginRow();
  void Double(double v);  // non-finite: NULL
  void Int(int64_t v);
  // ids[index], or NULL for an index out of range (-1: the static world, no robot).
  void Id(const std::vector<int64_t>& ids, int64_t index);
  void Text(std::string_view text);
  // A literal SQL expression (multi-row INSERT only).
  void Expression(const std::string& sql);
  void EndRow();
  // Sends what is left; throws DbError, or ScratchFileError for LOAD DATA.
  void Finish() { Flush(); }
  uint64_t rows() const { return rows_; }

 private:
  void Start();
  void Separator();
  void Flush();
  void WriteFile(const std::string& what);

  DbConnection* db_;
  bool load_data_;
  std::string scratch_path_;
  std::string table_;
  std::string columns_;
  std::string on_duplicate_;
  std::string buffer_;
  bool first_field_ = true;
  size_t rows_in_buffer_ = 0;
  uint64_t rows_ = 0;
};

}  // namespace simpartner::logger
