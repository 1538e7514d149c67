// Sensor readings, commands and command replies of a run as rows: few, and
// keyed so that writing them again is a no-op.
#pragma once

#include <cstdint>
#include <vector>

#include "row_sink.h"
#include "simpartner/logger/record.h"
#include "simpartner/logger/writer.h"

namespace simpartner::logger {

class EventRows {
 public:
  explicit EventRows(DbConnection* db);
  // A kSensor, kCommand or kCommandReply record of `simulation`, whose
  // sensors have `sensor_ids` (by bus index). One that does not decode is
  // reported through `notice` and left out.
  void Add(const Record& record, uint32_t simulation, const std::vector<int64_t>& sensor_ids,
           const DbWriter::Notice& notice);
  // Sends the rows; returns how many.
  uint64_t Finish();

 private:
  void AddReading(const Record& record, uint32_t simulation, const std::vector<int64_t>& sensor_ids,
                  const DbWriter::Notice& notice);
  void AddCommand(const Record& record, uint32_t simulation, const DbWriter::Notice& notice);
  void AddReply(const Record& record, uint32_t simulation, const DbWriter::Notice& notice);

  RowSink readings_, commands_, replies_;
};

}  // namespace simpartner::logger
