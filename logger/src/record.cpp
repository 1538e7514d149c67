#include "simpartner/logger/record.h"

#include <cstring>
#include <stdexcept>

namespace simpartner::logger {
namespace {

void PutI64(std::vector<uint8_t>* out, int64_t value) {
  // resize + memcpy: GCC 12 at -O3 sees a false overflow in the inlined
  // vector::insert of a byte range (-Wstringop-overflow).
  const size_t at = out->size();
  out->resize(at + 8);
  std::memcpy(out->data() + at, &value, 8);
}

int64_t GetI64(const std::vector<uint8_t>& in, size_t offset) {
  int64_t value;
  std::memcpy(&value, in.data() + offset, 8);
  return value;
}

void CheckSize(const Record& record, size_t size, bool more_allowed) {
  if (record.payload.size() < size || (!more_allowed && record.payload.size() != size))
    throw std::runtime_error(std::string(RecordKindName(record.kind)) + " record has " +
                             std::to_string(record.payload.size()) + " payload bytes, expected " +
                             (more_allowed ? "at least " : "") + std::to_string(size));
}

std::string TextFrom(const Record& record, size_t offset) {
  if (record.payload.size() <= offset) return "";
  return std::string(record.payload.begin() + static_cast<std::ptrdiff_t>(offset),
                     record.payload.end());
}

}  // namespace

const char* RecordKindName(RecordKind kind) {
  switch (kind) {
    case RecordKind::kModel: return "model";
    case RecordKind::kState: return "state";
    case RecordKind::kSensor: return "sensor reading";
    case RecordKind::kCommand: return "command";
    case RecordKind::kCommandReply: return "command reply";
    case RecordKind::kSimulationEnded: return "simulation ended";
    case RecordKind::kGap: return "gap";
    case RecordKind::kSimulationReopened: return "simulation reopened";
  }
  return "unknown";
}

bool IsKnownRecordKind(uint8_t kind) { return kind >= 1 && kind <= 8; }

Record MakeGapRecord(int64_t simulation_id, int64_t received_us, const GapPayload& gap) {
  Record r;
  r.kind = RecordKind::kGap;
  r.simulation_id = simulation_id;
  r.received_us = received_us;
  PutI64(&r.payload, gap.first_step);
  PutI64(&r.payload, gap.last_step);
  PutI64(&r.payload, gap.missing);
  r.payload.insert(r.payload.end(), gap.reason.begin(), gap.reason.end());
  return r;
}

Record MakeEndedRecord(int64_t simulation_id, int64_t received_us, const EndedPayload& ended) {
  Record r;
  r.kind = RecordKind::kSimulationEnded;
  r.simulation_id = simulation_id;
  r.received_us = received_us;
  PutI64(&r.payload, ended.last_step);
  PutI64(&r.payload, static_cast<int64_t>(ended.kind));
  r.payload.insert(r.payload.end(), ended.reason.begin(), ended.reason.end());
  return r;
}

Record MakeReopenedRecord(int64_t simulation_id, int64_t received_us, const std::string& reason) {
  Record r;
  r.kind = RecordKind::kSimulationReopened;
  r.simulation_id = simulation_id;
  r.received_us = received_us;
  r.payload.assign(reason.begin(), reason.end());
  return r;
}

GapPayload ReadGap(const Record& record) {
  CheckSize(record, 24, true);
  return GapPayload{GetI64(record.payload, 0), GetI64(record.payload, 8),
                    GetI64(record.payload, 16), TextFrom(record, 24)};
}

EndedPayload ReadEnded(const Record& record) {
  if (record.payload.size() == 8) return EndedPayload{GetI64(record.payload, 0), EndKind::kStopped, ""};
  CheckSize(record, 16, true);
  const int64_t kind = GetI64(record.payload, 8);
  return EndedPayload{GetI64(record.payload, 0), kind == 1 ? EndKind::kSilent : EndKind::kStopped,
                      TextFrom(record, 16)};
}

std::string ReadReopened(const Record& record) { return TextFrom(record, 0); }

}  // namespace simpartner::logger
