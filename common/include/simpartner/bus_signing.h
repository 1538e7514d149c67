// Signed bus messages: every message a process publishes is signed and
// every message it reads must carry a valid, fresh signature. On by
// default: with SIMPARTNER_BUS_KEY unset, a process signs with the user's
// key (UserBusKeyPath), made on first use; SIMPARTNER_BUS_KEY=FILE names
// another key file (32 random bytes or 64 hex digits, mode 0600), and
// SIMPARTNER_BUS_KEY=none makes the bus unsigned, said once at start.
//
// The anchor is MAVLink 2's message signing (a link id, a timestamp and a
// truncated SHA-256 signature, with replay protection). A signed message is
// the LCM-encoded message followed by a 36-byte trailer:
//
//   link id    8 bytes  random per publishing process: names its stream
//   timestamp  8 bytes  [us] since the Unix epoch, strictly increasing per link
//                       as sent (readers accept a little reordering)
//   tag       16 bytes  HMAC-SHA-256(key, "SPS1" channel NUL message link timestamp),
//                       the first 16 bytes (MAVLink keeps 6; 16 make a forgery
//                       a 2^-128 guess)
//   magic      4 bytes  "SPS1"
//
// A reader refuses a message whose tag is wrong, whose timestamp it has
// accepted from its link already or that is older than the link's replay
// window (a replay), or, from a link it has not seen, more than
// kFreshnessSeconds from its own clock (a replayed log). The replay
// window is IPsec's and DTLS's (RFC 4303 3.4.3, RFC 6347 4.1.2.6) over
// timestamps: UDP multicast may reorder datagrams, so a message older
// than the newest of its link is still accepted once if it is at most
// kReplayWindowMicros older and among the last kReplayWindowMessages
// (the accepted ones are remembered, per link, that far back). The
// stock LCM tools keep working: lcm-spy and lcm-logger decode the message
// and ignore the trailing bytes. HMAC-SHA-256 is OpenSSL's (libcrypto: it
// uses the CPU's SHA instructions, about 4 us for a 9 KB gen4 state, where
// libsodium's portable SHA-256 took about 20).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace simpartner {

inline constexpr size_t kSignatureBytes = 36;
inline constexpr const char* kBusKeyVariable = "SIMPARTNER_BUS_KEY";
// The value of SIMPARTNER_BUS_KEY that makes a process unsigned, by choice.
inline constexpr const char* kNoBusKey = "none";
// Where a program says a line about its key (the program adds its name);
// empty: nothing is said.
using BusKeyNote = std::function<void(const std::string& line)>;

class BusKeyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class BusSigning {
 public:
  using Key = std::array<uint8_t, 32>;
  static constexpr int64_t kFreshnessSeconds = 60;
  static constexpr size_t kMaxLinks = 4096;
  // The replay window of a link: how much older than its newest message a
  // message may be, and how many accepted timestamps are remembered (8
  // bytes each: at most 2 MiB for kMaxLinks links).
  static constexpr int64_t kReplayWindowMicros = 1000000;
  static constexpr size_t kReplayWindowMessages = 64;

  // The key of ChooseBusKeyFile(say), or nothing for "none". Throws
  // BusKeyError naming the file and what is wrong with it (missing, not
  // 32 bytes or 64 hex digits, readable by others).
  static std::optional<BusSigning> FromEnvironment(const BusKeyNote& say);
  static Key LoadKey(const std::string& path);

  // `key_file`: where the key came from, for the lines that name it.
  explicit BusSigning(const Key& key, std::string key_file = "");
  // Moves the key and the replay state (not while another thread uses it).
  BusSigning(BusSigning&& other) noexcept;
  BusSigning& operator=(BusSigning&& other) noexcept;
  BusSigning(const BusSigning&) = delete;
  BusSigning& operator=(const BusSigning&) = delete;

  // `size` bytes of an encoded message, signed for `channel`.
  std::vector<uint8_t> Sign(const std::string& channel, const void* data, size_t size);
  // The same, dated `now_us` (tests choose it); still after the last one
  // this signer dated.
  std::vector<uint8_t> Sign(const std::string& channel, const void* data, size_t size,
                            int64_t now_us);

  // The message's size without its signature when it verifies and is
  // fresh; else why not ("no signature", "wrong signature", "replayed:
  // ...", "stale: ..."). `now_us`: the reader's clock.
  enum class Verdict {
    kVerified,        // or read without a key
    kUnsigned,        // no signature trailer
    kWrongSignature,  // another key, or altered on the way
    kReplayedOrStale,
  };
  struct Opened {
    size_t size = 0;
    std::string refusal;  // "" when it verifies
    Verdict verdict = Verdict::kVerified;
  };
  Opened Open(const std::string& channel, const void* data, size_t size, int64_t now_us);

  const std::string& key_file() const { return key_file_; }

 private:
  void Tag(const std::string& channel, const uint8_t* data, size_t size, uint64_t link,
           int64_t timestamp, uint8_t out[16]) const;

  Key key_;
  std::string key_file_;
  uint64_t link_;
  std::mutex mutex_;  // a client publishes and reads on two threads
  int64_t last_sent_ = 0;
  // A link's replay window: every timestamp accepted at or above `floor`
  // is in `recent`; nothing below `floor` is accepted. `used`: when it was
  // last read (the least recently read link goes first when kMaxLinks are
  // known).
  struct Link {
    int64_t newest = 0;
    int64_t floor = 0;
    std::vector<int64_t> recent;  // ascending, at most kReplayWindowMessages
    uint64_t used = 0;
  };
  // Takes `timestamp` into `link`'s window: "" when it is new and within
  // it, else why it is refused.
  static std::string Admit(Link* link, int64_t timestamp);
  std::map<uint64_t, Link> links_;
  uint64_t uses_ = 0;
};

// The user's bus key: $XDG_CONFIG_HOME/simpartner/bus.key, else
// ~/.config/simpartner/bus.key (the XDG base directory rule: a relative
// XDG_CONFIG_HOME is ignored). Throws BusKeyError when HOME is not set
// either.
std::string UserBusKeyPath();

// Makes a key file at `path` unless something is there: 32 random bytes
// as 64 hex digits, mode 0600, its missing directories mode 0700. The
// programs of a run start at once: the key is written aside and linked
// into place, so every one of them reads the key that was linked first.
// True when this call made it; throws BusKeyError naming the path.
bool MakeBusKeyIfMissing(const std::string& path);

// The key file this process signs with, as SIMPARTNER_BUS_KEY says: the
// file it names; "" for "none" (unsigned by choice); unset or empty, the
// user's key, made when missing. Tells `say` that the bus is unsigned,
// or where the key was made.
std::string ChooseBusKeyFile(const BusKeyNote& say);

// The message's size without a signature trailer, for a reader without a
// key: it cannot check the signature and reads the message as unsigned.
size_t UnsignedSize(const void* data, size_t size);
// The link id of a signed message (its publishing process's stream), 0
// for one without a signature trailer. Only what BusSigning::Open has
// verified says who sent it.
uint64_t SigningLink(const void* data, size_t size);

// A datagram read from the bus, before decoding: with `signing`, checked
// (Open, at this host's clock); without, its signature trailer dropped
// unread (UnsignedSize). The one step every reader takes.
BusSigning::Opened OpenMessage(BusSigning* signing, const std::string& channel, const void* data,
                               size_t size);

// Why a reader may hear no answer although messages come: what it heard
// about signatures. Without a key: messages that carry one (the bus is
// signed, and the sim refuses what this reader sends unsigned). With a
// key: messages without one (the sim runs unsigned), or whose signature
// does not verify (another key). Not thread-safe: the caller's lock.
class SigningMismatch {
 public:
  // After OpenMessage(signing, ...) of one datagram (`has_key`: signing
  // was set).
  void Note(bool has_key, const void* data, size_t size, const BusSigning::Opened& opened);
  // "" when nothing heard suggests a mismatch; else what was heard and
  // what to do, in a sentence that names SIMPARTNER_BUS_KEY and
  // docs/security.md.
  std::string Hint() const;

 private:
  bool has_key_ = false;
  uint64_t signed_unchecked_ = 0;  // without a key: messages with a signature
  uint64_t unsigned_refused_ = 0;  // with a key
  uint64_t wrong_signature_ = 0;   // with a key
  uint64_t verified_ = 0;          // with a key
};

// Publishes `message` on `channel`, signed when `signing` is set. Returns
// lcm's status (0 when sent).
template <class T>
int PublishSigned(lcm::LCM* lcm, const std::string& channel, const T& message,
                  BusSigning* signing) {
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  if (signing != nullptr) bytes = signing->Sign(channel, bytes.data(), bytes.size());
  return lcm->publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}

}  // namespace simpartner
