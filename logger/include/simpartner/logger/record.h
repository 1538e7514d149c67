// What travels from the receive thread to the database writer, through the
// memory queue or the spool on disk: the message as it came off the bus
// (already checked by the receiver), with the simulation it belongs to.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace simpartner::logger {

enum class RecordKind : uint8_t {
  kModel = 1,            // payload: model_t as on the bus
  kState = 2,            // payload: state_t
  kSensor = 3,           // payload: sensor_reading_t
  kCommand = 4,          // payload: command_t (simulation = the one meant, if known, else the one followed)
  kCommandReply = 5,     // payload: command_reply_t
  kSimulationEnded = 6,  // payload: EndedPayload (the sim stopped, or went silent)
  kGap = 7,              // payload: GapPayload (steps the logger could not keep)
  // payload: the reason (text). A simulation closed because its sim went
  // silent is heard again (it was stopped, or its link was down): it is
  // open again, and the silence follows as a kGap record.
  kSimulationReopened = 8,
};

const char* RecordKindName(RecordKind kind);
bool IsKnownRecordKind(uint8_t kind);

struct Record {
  RecordKind kind = RecordKind::kState;
  int64_t simulation_id = 0;  // bus simulation id (model_t.simulation_id)
  int64_t received_us = 0;    // wall clock when the logger received it
  std::vector<uint8_t> payload;

  size_t ByteSize() const { return payload.size() + 32; }
};

// Steps first_step..last_step (every `stride`-th) of a simulation that the
// logger received but could not keep (e.g. its spool disk was full), and
// why: what LogGap.reason says.
struct GapPayload {
  int64_t first_step = 0;
  int64_t last_step = 0;
  int64_t missing = 0;
  std::string reason;
};

enum class EndKind : int64_t {
  kStopped = 0,  // the sim said RUN_STOPPED
  kSilent = 1,   // nothing from the sim for a while: it died, or a kSimulationReopened follows
};

// How the reason of a simulation closed because its sim went silent begins
// (Simulation.endReason): such a close is undone when the sim talks again.
inline constexpr const char* kSilentReasonStart = "the sim went silent: ";

struct EndedPayload {
  int64_t last_step = 0;  // the sim's last step (stopped) or the last one seen (silent)
  EndKind kind = EndKind::kStopped;
  std::string reason;     // for Simulation.endReason ("" = "the sim stopped")
};

Record MakeGapRecord(int64_t simulation_id, int64_t received_us, const GapPayload& gap);
Record MakeEndedRecord(int64_t simulation_id, int64_t received_us, const EndedPayload& ended);
Record MakeReopenedRecord(int64_t simulation_id, int64_t received_us, const std::string& reason);
// Throw std::runtime_error if the payload has the wrong size. Records of an
// older spool (without kind and reason) read with the defaults.
GapPayload ReadGap(const Record& record);
EndedPayload ReadEnded(const Record& record);
std::string ReadReopened(const Record& record);

}  // namespace simpartner::logger
