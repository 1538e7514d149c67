#include "simpartner/bus_signing.h"

#include <openssl/core_names.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/rand.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "simpartner/bounded_file.h"
#include "simpartner/random_token.h"
#include "simpartner/sender.h"

namespace simpartner {
namespace {

constexpr uint8_t kMagic[4] = {'S', 'P', 'S', '1'};

void PutBigEndian(uint64_t value, uint8_t* out) {
  for (int i = 7; i >= 0; --i, value >>= 8) out[i] = static_cast<uint8_t>(value & 0xff);
}

uint64_t GetBigEndian(const uint8_t* in) {
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = value << 8 | in[i];
  return value;
}

// 64 hex digits to the key; false when they are not.
bool FromHex(const std::string& text, BusSigning::Key* key) {
  if (text.size() != 2 * key->size()) return false;
  for (size_t i = 0; i < key->size(); ++i) {
    unsigned value = 0;
    for (const char c : {text[2 * i], text[2 * i + 1]}) {
      if (!std::isxdigit(static_cast<unsigned char>(c))) return false;
      value = value * 16 +
              static_cast<unsigned>(std::isdigit(static_cast<unsigned char>(c))
                                        ? c - '0'
                                        : std::tolower(static_cast<unsigned char>(c)) - 'a' + 10);
    }
    (*key)[i] = static_cast<uint8_t>(value);
  }
  return true;
}

}  // namespace

BusSigning::Key BusSigning::LoadKey(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && (info.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(info.st_mode & 07777));
    throw BusKeyError(path + ": bus key file readable by others (mode " + mode +
                      "): chmod 600 it");
  }
  std::string text;
  try {
    text = ReadBoundedFile(path, 1024, "bus key files");
  } catch (const FileReadError& e) {
    throw BusKeyError(path + ": " + (e.cannot_open() ? "cannot read the bus key file: " : "") +
                      e.what());
  }
  Key key{};
  if (text.size() == key.size()) {
    std::copy(text.begin(), text.end(), key.begin());
    return key;
  }
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  if (!FromHex(text, &key))
    throw BusKeyError(path + ": a bus key file holds 32 bytes or 64 hex digits, this one " +
                      std::to_string(text.size()) +
                      " bytes (make one: head -c 32 /dev/urandom > FILE; chmod 600 FILE)");
  return key;
}

std::optional<BusSigning> BusSigning::FromEnvironment(const BusKeyNote& say) {
  const std::string path = ChooseBusKeyFile(say);
  if (path.empty()) return std::nullopt;
  return std::optional<BusSigning>(std::in_place, LoadKey(path), path);
}

std::string UserBusKeyPath() {
  const char* config = std::getenv("XDG_CONFIG_HOME");
  if (config != nullptr && config[0] == '/') return std::string(config) + "/simpartner/bus.key";
  const char* home = std::getenv("HOME");
  if (home == nullptr || home[0] != '/')
    throw BusKeyError(std::string("no place for the user's bus key: neither XDG_CONFIG_HOME nor "
                                  "HOME is an absolute path; set ") +
                      kBusKeyVariable + " to a key file (docs/security.md)");
  return std::string(home) + "/.config/simpartner/bus.key";
}

namespace {

// Why the user's key could not be made, and the way around it.
BusKeyError CannotMakeKey(const std::string& what, int error) {
  return BusKeyError(what + ": " + std::strerror(error) + " (or set " + kBusKeyVariable +
                     " to a key file: docs/security.md)");
}

// `dir` and its missing parents, each made mode 0700: a key's directory
// is its user's alone.
void MakeKeyDirectories(const std::filesystem::path& dir) {
  std::error_code ignored;
  if (dir.empty() || std::filesystem::is_directory(dir, ignored)) return;
  if (dir.has_relative_path() && dir.parent_path() != dir) MakeKeyDirectories(dir.parent_path());
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw CannotMakeKey(dir.string() + ": cannot make the bus key's directory", errno);
}

// `text` in the new file `fd`, on the disk.
bool WriteNewKey(int fd, const std::string& text) {
  return ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) &&
         ::fsync(fd) == 0;
}

}  // namespace

bool MakeBusKeyIfMissing(const std::string& path) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) == 0) return false;
  MakeKeyDirectories(std::filesystem::path(path).parent_path());
  // 32 random bytes as 64 hex digits and a newline: a key a person can
  // copy as text.
  std::string text;
  try {
    text = RandomToken(BusSigning::Key().size()) + "\n";
  } catch (const std::runtime_error& e) {
    throw BusKeyError(path + ": " + e.what());
  }
  std::string aside = path + ".XXXXXX";
  const int fd = ::mkstemp(aside.data());  // mode 0600
  if (fd < 0) throw CannotMakeKey(path + ": cannot write a bus key beside it", errno);
  const bool written = WriteNewKey(fd, text);
  const int write_error = errno;
  ::close(fd);
  if (!written) {
    ::unlink(aside.c_str());
    throw CannotMakeKey(aside + ": cannot write a bus key", write_error);
  }
  // link fails when the name exists: of programs starting at once, the
  // first to link wins, and the others read its key.
  const bool linked = ::link(aside.c_str(), path.c_str()) == 0;
  const int link_error = errno;
  ::unlink(aside.c_str());
  if (linked) return true;
  if (link_error == EEXIST) return false;
  throw CannotMakeKey(path + ": cannot put the bus key in place", link_error);
}

std::string ChooseBusKeyFile(const BusKeyNote& say) {
  const char* chosen = std::getenv(kBusKeyVariable);
  if (chosen != nullptr && std::strcmp(chosen, kNoBusKey) == 0) {
    if (say)
      say(std::string("the bus is unsigned (") + kBusKeyVariable + "=" + kNoBusKey +
          "): any process that can reach it can command the robot and feed every reader "
          "(docs/security.md)");
    return "";
  }
  if (chosen != nullptr && *chosen != '\0') return chosen;
  const std::string path = UserBusKeyPath();
  if (MakeBusKeyIfMissing(path) && say)
    say("made the bus key " + path +
        " (mode 0600): every SimPartner program of this user signs with it; copy it to the "
        "machines that share the bus (docs/several-machines.md)");
  return path;
}

BusSigning::BusSigning(const Key& key, std::string key_file)
    : key_(key), key_file_(std::move(key_file)) {
  if (RAND_bytes(reinterpret_cast<unsigned char*>(&link_), sizeof link_) != 1)
    throw BusKeyError("OpenSSL has no random bytes for a link id");
}

BusSigning::BusSigning(BusSigning&& other) noexcept
    : key_(other.key_),
      key_file_(std::move(other.key_file_)),
      link_(other.link_),
      last_sent_(other.last_sent_),
      links_(std::move(other.links_)),
      uses_(other.uses_) {}

BusSigning& BusSigning::operator=(BusSigning&& other) noexcept {
  key_ = other.key_;
  key_file_ = std::move(other.key_file_);
  link_ = other.link_;
  last_sent_ = other.last_sent_;
  links_ = std::move(other.links_);
  uses_ = other.uses_;
  return *this;
}

void BusSigning::Tag(const std::string& channel, const uint8_t* data, size_t size, uint64_t link,
                     int64_t timestamp, uint8_t out[16]) const {
  uint8_t stamp[16];
  PutBigEndian(link, stamp);
  PutBigEndian(static_cast<uint64_t>(timestamp), stamp + 8);
  // OpenSSL's HMAC, fetched once (immutable, shared by threads); a
  // context per call: a client signs and checks on two threads.
  static EVP_MAC* const mac = EVP_MAC_fetch(nullptr, "HMAC", nullptr);
  EVP_MAC_CTX* context = mac ? EVP_MAC_CTX_new(mac) : nullptr;
  char digest[] = "SHA256";
  const OSSL_PARAM params[] = {
      OSSL_PARAM_construct_utf8_string(OSSL_MAC_PARAM_DIGEST, digest, 0), OSSL_PARAM_construct_end()};
  uint8_t full[EVP_MAX_MD_SIZE];
  size_t length = 0;
  const bool done =
      context && EVP_MAC_init(context, key_.data(), key_.size(), params) == 1 &&
      EVP_MAC_update(context, kMagic, sizeof kMagic) == 1 &&
      EVP_MAC_update(context, reinterpret_cast<const uint8_t*>(channel.c_str()),
                     channel.size() + 1) == 1 &&  // with its NUL
      EVP_MAC_update(context, data, size) == 1 &&
      EVP_MAC_update(context, stamp, sizeof stamp) == 1 &&
      EVP_MAC_final(context, full, &length, sizeof full) == 1 && length >= 16;
  EVP_MAC_CTX_free(context);
  if (!done) throw BusKeyError("OpenSSL could not compute HMAC-SHA-256");
  std::memcpy(out, full, 16);
}

std::vector<uint8_t> BusSigning::Sign(const std::string& channel, const void* data, size_t size) {
  return Sign(channel, data, size, WallMicros());
}

std::vector<uint8_t> BusSigning::Sign(const std::string& channel, const void* data, size_t size,
                                      int64_t now_us) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  std::vector<uint8_t> out(bytes, bytes + size);
  out.resize(size + kSignatureBytes);
  int64_t timestamp;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    timestamp = std::max(now_us, last_sent_ + 1);
    last_sent_ = timestamp;
  }
  uint8_t* trailer = out.data() + size;
  PutBigEndian(link_, trailer);
  PutBigEndian(static_cast<uint64_t>(timestamp), trailer + 8);
  Tag(channel, bytes, size, link_, timestamp, trailer + 16);
  std::memcpy(trailer + 32, kMagic, sizeof kMagic);
  return out;
}

BusSigning::Opened BusSigning::Open(const std::string& channel, const void* data, size_t size,
                                    int64_t now_us) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (size < kSignatureBytes || std::memcmp(bytes + size - 4, kMagic, 4) != 0)
    return {size, "no signature (this bus is signed: SIMPARTNER_BUS_KEY)", Verdict::kUnsigned};
  const size_t message = size - kSignatureBytes;
  const uint8_t* trailer = bytes + message;
  const uint64_t link = GetBigEndian(trailer);
  const int64_t timestamp = static_cast<int64_t>(GetBigEndian(trailer + 8));
  uint8_t expected[16];
  Tag(channel, bytes, message, link, timestamp, expected);
  if (CRYPTO_memcmp(expected, trailer + 16, 16) != 0)
    return {message, "wrong signature (another key, or altered on the way)",
            Verdict::kWrongSignature};
  std::lock_guard<std::mutex> lock(mutex_);
  const auto known = links_.find(link);
  if (known != links_.end()) {
    const std::string refusal = Admit(&known->second, timestamp);
    if (refusal.empty()) known->second.used = ++uses_;
    return {message, refusal, refusal.empty() ? Verdict::kVerified : Verdict::kReplayedOrStale};
  }
  if (std::llabs(timestamp - now_us) > kFreshnessSeconds * 1000000)
    return {message, "stale: a new sender's first message, " +
                         std::to_string((now_us - timestamp) / 1000000) +
                         " s from this host's clock (at most " +
                         std::to_string(kFreshnessSeconds) + " s: a replayed log?)",
            Verdict::kReplayedOrStale};
  if (links_.size() >= kMaxLinks) {
    const auto oldest = std::min_element(
        links_.begin(), links_.end(),
        [](const auto& a, const auto& b) { return a.second.used < b.second.used; });
    links_.erase(oldest);
  }
  // A new link: what came just before its first message may still come.
  links_[link] = Link{timestamp, timestamp - kReplayWindowMicros, {timestamp}, ++uses_};
  return {message, ""};
}

std::string BusSigning::Admit(Link* link, int64_t timestamp) {
  if (timestamp < link->floor)
    return "replayed: timestamp " + std::to_string(timestamp) + " us is " +
           std::to_string(link->newest - timestamp) +
           " us before the newest of its sender, older than its replay window (the last " +
           std::to_string(kReplayWindowMessages) + " messages within " +
           std::to_string(kReplayWindowMicros) + " us)";
  std::vector<int64_t>& recent = link->recent;
  const auto at = std::lower_bound(recent.begin(), recent.end(), timestamp);
  if (at != recent.end() && *at == timestamp)
    return "replayed: timestamp " + std::to_string(timestamp) +
           " us was accepted from its sender already";
  recent.insert(at, timestamp);
  if (timestamp > link->newest) {
    link->newest = timestamp;
    link->floor = std::max(link->floor, timestamp - kReplayWindowMicros);
    recent.erase(recent.begin(), std::lower_bound(recent.begin(), recent.end(), link->floor));
  }
  if (recent.size() > kReplayWindowMessages) {  // forgotten: nothing at or below it again
    link->floor = recent.front() + 1;
    recent.erase(recent.begin());
  }
  return "";
}

BusSigning::Opened OpenMessage(BusSigning* signing, const std::string& channel, const void* data,
                               size_t size) {
  if (signing == nullptr) return {UnsignedSize(data, size), ""};
  return signing->Open(channel, data, size, WallMicros());
}

void SigningMismatch::Note(bool has_key, const void* data, size_t size,
                           const BusSigning::Opened& opened) {
  has_key_ = has_key;
  if (!has_key) {
    if (UnsignedSize(data, size) != size) ++signed_unchecked_;
    return;
  }
  switch (opened.verdict) {
    case BusSigning::Verdict::kVerified: ++verified_; break;
    case BusSigning::Verdict::kUnsigned: ++unsigned_refused_; break;
    case BusSigning::Verdict::kWrongSignature: ++wrong_signature_; break;
    case BusSigning::Verdict::kReplayedOrStale: break;
  }
}

std::string SigningMismatch::Hint() const {
  const std::string where = std::string(" (") + kBusKeyVariable + "; docs/security.md)";
  if (!has_key_ && signed_unchecked_ > 0)
    return "this bus is signed (" + std::to_string(signed_unchecked_) +
           " messages heard carry a signature) and this program has no key (" + kBusKeyVariable +
           "=" + kNoBusKey + "), so the sim refuses what it sends: set " + kBusKeyVariable +
           " to the bus's key file, or leave it unset (docs/security.md)";
  if (has_key_ && wrong_signature_ > 0)
    return std::to_string(wrong_signature_) + " messages heard did not verify with this program's key" +
           (verified_ == 0 ? ", and none did: the bus uses another key" : ": another key on the bus") +
           " (copy the sim's key file: docs/several-machines.md)" + where;
  if (has_key_ && unsigned_refused_ > 0 && verified_ == 0)
    return "the " + std::to_string(unsigned_refused_) +
           " messages heard are unsigned and this program has a key, so it refuses them: the sim "
           "runs without one (" + kBusKeyVariable + "=" + kNoBusKey + "); sign it, or set " +
           kBusKeyVariable + "=" + kNoBusKey + " here too" + where;
  return "";
}

size_t UnsignedSize(const void* data, size_t size) {
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (size >= kSignatureBytes && std::memcmp(bytes + size - 4, kMagic, 4) == 0)
    return size - kSignatureBytes;
  return size;
}

uint64_t SigningLink(const void* data, size_t size) {
  const size_t message = UnsignedSize(data, size);
  if (message == size) return 0;
  return GetBigEndian(static_cast<const uint8_t*>(data) + message);
}

}  // namespace simpartner
