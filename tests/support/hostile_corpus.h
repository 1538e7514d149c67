// Hostile datagrams for every channel of SPEC 5b: what an attacker or a
// broken peer on the network segment can send to our multicast group.
// Each is built byte by byte (not with lcm-gen's encoder, which cannot
// write a negative count or a zero string length), with a name that tests
// print, so a failure says which message did it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace simpartner::test_support {

struct HostileMessage {
  std::string name;     // e.g. "command_t sender length 0"
  std::string channel;  // where it is sent
  std::vector<uint8_t> bytes;
  // True when the bytes are not a message of the channel's type at all
  // (the decoder must refuse them); false when they decode but their
  // content is nonsense the receiver must refuse on its own.
  bool undecodable;
};

// At least 30 messages, every channel and message type. `simulation_id` is
// used where a message pretends to come from the running sim.
std::vector<HostileMessage> HostileCorpus(int64_t simulation_id);

// Big-endian writer for hand-made LCM datagrams.
class RawMessage {
 public:
  explicit RawMessage(int64_t hash) { I64(hash); }
  RawMessage& I8(int8_t v) { return Put(static_cast<uint64_t>(static_cast<uint8_t>(v)), 1); }
  RawMessage& I16(int16_t v) { return Put(static_cast<uint16_t>(v), 2); }
  RawMessage& I32(int32_t v) { return Put(static_cast<uint32_t>(v), 4); }
  RawMessage& I64(int64_t v) { return Put(static_cast<uint64_t>(v), 8); }
  RawMessage& F64(double v);
  RawMessage& F32(float v);
  RawMessage& Str(const std::string& s);  // well-formed string
  RawMessage& StrLength(int32_t length);  // a length field only (for bad ones)
  RawMessage& Zeros(size_t n) {
    bytes_.insert(bytes_.end(), n, 0);
    return *this;
  }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  RawMessage& Put(uint64_t v, int n) {
    for (int i = n - 1; i >= 0; --i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
    return *this;
  }
  std::vector<uint8_t> bytes_;
};

}  // namespace simpartner::test_support
