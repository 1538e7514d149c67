// libFuzzer target, built once per message type of the bus (SP_FUZZ_TYPE):
// arbitrary bytes after the type's fingerprint, as anyone on the network
// can send them. The total decoder must never crash, throw or allocate
// beyond the datagram's size, and what it accepts must encode back into a
// message it accepts again, unchanged, and be judged by its type's check
// (message_checks.h) without a crash.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "simpartner/bus_decode.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/message_checks.h"
#include "simpartner/model_request_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"

using Message = simpartner::SP_FUZZ_TYPE;

namespace {

// The check of each type that has one, alone and against a model outline
// as large as the message claims. Each build uses one overload: the others
// are [[maybe_unused]].
template <class T>
void Judge(const T&) {}
[[maybe_unused]] void Judge(const simpartner::model_t& m) {
  if (!simpartner::CheckModel(m)) (void)simpartner::OutlineOf(m);
}
[[maybe_unused]] void Judge(const simpartner::state_t& s) {
  simpartner::ModelOutline outline;
  outline.bodies = s.num_bodies;
  outline.joints = s.num_joints;
  (void)simpartner::CheckState(s, nullptr);
  (void)simpartner::CheckState(s, &outline);
}
[[maybe_unused]] void Judge(const simpartner::sensor_reading_t& r) {
  simpartner::ModelOutline outline;
  outline.sensors.resize(4);
  (void)simpartner::CheckSensorReading(r, nullptr);
  (void)simpartner::CheckSensorReading(r, &outline);
}
[[maybe_unused]] void Judge(const simpartner::status_t& s) { (void)simpartner::CheckStatus(s); }
[[maybe_unused]] void Judge(const simpartner::command_t& c) { (void)simpartner::CheckCommand(c); }
[[maybe_unused]] void Judge(const simpartner::command_reply_t& r) { (void)simpartner::CheckCommandReply(r); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The fingerprint is given, so the fuzzer spends its time on the body.
  std::vector<uint8_t> bytes(8 + size);
  const uint64_t hash = static_cast<uint64_t>(Message::getHash());
  for (int i = 0; i < 8; ++i) bytes[static_cast<size_t>(i)] = static_cast<uint8_t>(hash >> (56 - 8 * i));
  if (size > 0) std::memcpy(bytes.data() + 8, data, size);

  Message message;
  if (simpartner::DecodeLcm(bytes.data(), bytes.size(), &message)) return 0;  // refused: fine
  std::vector<uint8_t> again(static_cast<size_t>(message.getEncodedSize()));
  if (message.encode(again.data(), 0, static_cast<int>(again.size())) != static_cast<int>(again.size()))
    __builtin_trap();
  Message twice;
  if (simpartner::DecodeLcm(again.data(), again.size(), &twice)) __builtin_trap();
  std::vector<uint8_t> third(static_cast<size_t>(twice.getEncodedSize()));
  twice.encode(third.data(), 0, static_cast<int>(third.size()));
  if (third != again) __builtin_trap();
  Judge(message);
  return 0;
}
