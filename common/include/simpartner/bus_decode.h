// Total decoding of untrusted bus input. Every process that reads the bus
// decodes through here, never through lcm-gen's decode() directly.
//
// lcm-gen's C++ decoders trust the bytes: a string length of 0 or less
// throws std::length_error, and an array count is allocated before it is
// checked against the datagram (2^31-1 doubles is bad_alloc, 1e8 is 800 MB).
// Anyone on the network segment can send such a datagram to our multicast
// group. So a message is first walked field by field against its layout
// (generated from the .lcm files, lcm_schema.hpp): every string length must
// be at least 1 and fit, every count must be >= 0, within the bound the
// .lcm file states ("at most N") and small enough that its elements fit in
// the bytes left. Only then does lcm-gen's decoder run, and it allocates at
// most a small multiple of the datagram's size.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <map>
#include <optional>
#include <string>

#include "simpartner/bus_signing.h"
#include "simpartner/rate_limited_log.h"

namespace simpartner {

// Why a datagram was refused, for messages: "field 'sender': string length
// 0 (an LCM string holds at least its NUL)".
struct DecodeFailure {
  std::string reason;
};

// Checks that `data` holds exactly one message of the LCM type named
// `type_name` (e.g. "command_t") with fingerprint `hash`, without decoding
// it. Returns the first problem found, or nothing when lcm-gen's decoder
// can be run safely.
std::optional<DecodeFailure> CheckLcmLayout(const char* type_name, int64_t hash,
                                            const void* data, size_t size);

// Decodes one whole message of type T from untrusted bytes. Never throws,
// never allocates beyond a small multiple of `size`. On failure returns why
// and leaves *out unspecified.
template <class T>
std::optional<DecodeFailure> DecodeLcm(const void* data, size_t size, T* out) {
  if (size > static_cast<size_t>(INT32_MAX))
    return DecodeFailure{"message of " + std::to_string(size) + " bytes is larger than LCM allows"};
  if (auto failure = CheckLcmLayout(T::getTypeName(), T::getHash(), data, size)) return failure;
  try {
    const int used = out->decode(data, 0, static_cast<int>(size));
    if (used < 0) return DecodeFailure{"lcm-gen's decoder refused it"};
    if (static_cast<size_t>(used) != size)
      return DecodeFailure{std::to_string(size - static_cast<size_t>(used)) +
                           " bytes follow the message"};
  } catch (const std::exception& e) {
    // The layout check should make this unreachable; a failure here is a
    // bug in it, reported rather than fatal.
    return DecodeFailure{std::string("decoder threw: ") + e.what()};
  }
  return std::nullopt;
}

// The description every process prints and counts for a refused message:
// "SIM_COMMAND: 48 bytes refused as simpartner.command_t: field 'sender':
// string length 0 (...)".
std::string DescribeRefusal(const std::string& channel, const char* type_name, size_t size,
                            const DecodeFailure& failure);

// The description of a message refused for its signature or freshness:
// "SIM_COMMAND: 140 bytes refused: replayed: ...".
std::string DescribeSignatureRefusal(const std::string& channel, size_t size,
                                     const std::string& reason);

// Refused signed messages are named at most this often per receiver (a
// process has one), each line saying how many were refused since the last.
inline constexpr std::chrono::seconds kSignatureReportPeriod{1};

// Refused messages counted per channel, with the newest description of
// each, for a process's status output. Not thread-safe: one per receiver.
class BadMessageCounter {
 public:
  // Records one refused message; returns true when it should be printed
  // (the first of a channel, then one in every `print_every`), so a flood
  // does not become a flood of log lines.
  bool Count(const std::string& channel, const std::string& description);
  // Records a message refused for its signature or freshness (bus_signing.h);
  // returns the line to print now: `description` with how many were
  // refused since the last such line, at most one a kSignatureReportPeriod
  // (on any channel), else nothing.
  std::optional<std::string> CountSignatureRefusal(const std::string& channel,
                                                   const std::string& description,
                                                   RateLimitedLog::Clock::time_point now);
  uint64_t total() const { return total_; }
  uint64_t count(const std::string& channel) const;
  const std::map<std::string, uint64_t>& per_channel() const { return counts_; }
  // "SIM_COMMAND 3, SIM_STATE 1" (channels in name order), or "" when none.
  std::string Summary() const;
  const std::string& last_description() const { return last_; }

  static constexpr uint64_t kPrintEvery = 1000;

 private:
  std::map<std::string, uint64_t> counts_;
  uint64_t total_ = 0;
  std::string last_;
  RateLimitedLog signature_lines_{kSignatureReportPeriod, "more refused"};
};

// Decodes `data` as T for `channel`; on failure counts it in `counter` and
// returns the description (also when it should not be printed: see
// `print`). The one call every subscriber makes.
template <class T>
std::optional<std::string> DecodeFromBus(const std::string& channel, const void* data, size_t size,
                                         T* out, BadMessageCounter* counter, bool* print = nullptr) {
  auto failure = DecodeLcm(data, size, out);
  if (!failure) return std::nullopt;
  std::string description = DescribeRefusal(channel, T::getTypeName(), size, *failure);
  const bool should_print = counter ? counter->Count(channel, description) : true;
  if (print) *print = should_print;
  return description;
}

// A datagram read from the bus, before decoding: with `signing`, its
// signature must verify and be fresh (bus_signing.h); without, a signature
// trailer is dropped unread. Returns the message's size, or counts the
// refusal in `counter` and returns nothing with the description in
// *refusal; *print says whether to print it now (CountSignatureRefusal:
// at most a line a second, with the count since the last). `mismatch`,
// if given, notes what the datagram tells of the bus's signing.
std::optional<size_t> OpenFromBus(const std::string& channel, const void* data, size_t size,
                                  BusSigning* signing, BadMessageCounter* counter,
                                  std::string* refusal, bool* print = nullptr,
                                  SigningMismatch* mismatch = nullptr);

// OpenFromBus, then DecodeFromBus: the one call every subscriber makes.
template <class T>
std::optional<std::string> DecodeSigned(const std::string& channel, const void* data, size_t size,
                                        BusSigning* signing, T* out, BadMessageCounter* counter,
                                        bool* print = nullptr) {
  std::string refusal;
  const std::optional<size_t> message =
      OpenFromBus(channel, data, size, signing, counter, &refusal, print);
  if (!message) return refusal;
  return DecodeFromBus(channel, data, *message, out, counter, print);
}

}  // namespace simpartner
