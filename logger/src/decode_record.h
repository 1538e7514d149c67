// A record's payload decoded through the shared total decoder (the spool
// on disk is no more trusted than the bus).
#pragma once

#include <optional>
#include <string>

#include "simpartner/bus_decode.h"
#include "simpartner/logger/record.h"
#include "simpartner/logger/writer.h"

namespace simpartner::logger {

// A record that does not decode is reported through `notice` and skipped
// (false): retrying it could never succeed.
template <class Message>
bool DecodeRecord(const Record& record, Message* message, const DbWriter::Notice& notice) {
  const std::optional<DecodeFailure> failure =
      DecodeLcm(record.payload.data(), record.payload.size(), message);
  if (!failure) return true;
  notice(std::string("a ") + RecordKindName(record.kind) + " record of bus simulation " +
         std::to_string(record.simulation_id) + " does not decode; not written: " +
         DescribeRefusal("spool", Message::getTypeName(), record.payload.size(), *failure));
  return false;
}

}  // namespace simpartner::logger
