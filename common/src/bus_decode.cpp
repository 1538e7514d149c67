#include "simpartner/bus_decode.h"

#include <algorithm>
#include <array>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <vector>

#include "simpartner/lcm_schema.hpp"
#include "simpartner/sender.h"

namespace simpartner {
namespace {

using lcm_schema::Field;
using lcm_schema::Kind;
using lcm_schema::Type;

constexpr int64_t kUnknownSize = -1;

int PrimitiveSize(Kind kind) {
  switch (kind) {
    case Kind::kInt8:
    case Kind::kByte:
    case Kind::kBoolean: return 1;
    case Kind::kInt16: return 2;
    case Kind::kInt32:
    case Kind::kFloat: return 4;
    case Kind::kInt64:
    case Kind::kDouble: return 8;
    case Kind::kString:
    case Kind::kStruct: return 0;
  }
  return 0;
}

// Sizes of each type, worked out once from the table: the least bytes an
// element can take (bounds how many elements a count may claim) and the
// exact size when the type has no strings or variable arrays (lets arrays
// of such structs, e.g. state_t's bodies, be skipped without walking).
struct TypeSizes {
  std::array<int64_t, lcm_schema::kNumTypes> min{};
  std::array<int64_t, lcm_schema::kNumTypes> fixed{};
};

int64_t FixedCount(const Field& f) {
  int64_t n = 1;
  for (int d = 0; d < f.num_dims; ++d) {
    if (f.dims[d].count_field >= 0) return kUnknownSize;
    n *= f.dims[d].fixed;
  }
  return n;
}

void ComputeSizes(int type, TypeSizes* sizes, std::array<bool, lcm_schema::kNumTypes>* done) {
  if ((*done)[static_cast<size_t>(type)]) return;
  const Type& t = lcm_schema::kTypes[type];
  int64_t min = 0;
  int64_t fixed = 0;
  for (int i = 0; i < t.num_fields; ++i) {
    const Field& f = t.fields[i];
    int64_t element_min;
    int64_t element_fixed;
    if (f.kind == Kind::kStruct) {
      ComputeSizes(f.struct_type, sizes, done);
      element_min = sizes->min[static_cast<size_t>(f.struct_type)];
      element_fixed = sizes->fixed[static_cast<size_t>(f.struct_type)];
    } else if (f.kind == Kind::kString) {
      element_min = 5;  // int32 length + NUL
      element_fixed = kUnknownSize;
    } else {
      element_min = element_fixed = PrimitiveSize(f.kind);
    }
    const int64_t count = FixedCount(f);
    if (count == kUnknownSize) {
      fixed = kUnknownSize;  // a variable array may be empty
      continue;
    }
    min += count * element_min;
    if (fixed != kUnknownSize)
      fixed = element_fixed == kUnknownSize ? kUnknownSize : fixed + count * element_fixed;
  }
  sizes->min[static_cast<size_t>(type)] = min;
  sizes->fixed[static_cast<size_t>(type)] = fixed;
  (*done)[static_cast<size_t>(type)] = true;
}

TypeSizes MakeSizes() {
  TypeSizes sizes;
  std::array<bool, lcm_schema::kNumTypes> done{};
  for (int t = 0; t < lcm_schema::kNumTypes; ++t) ComputeSizes(t, &sizes, &done);
  return sizes;
}

const TypeSizes& Sizes() {
  static const TypeSizes sizes = MakeSizes();  // constant after first use
  return sizes;
}

int FindType(const char* name) {
  for (int t = 0; t < lcm_schema::kNumTypes; ++t)
    if (std::strcmp(lcm_schema::kTypes[t].name, name) == 0) return t;
  return -1;
}

// Walks a buffer against the layout table; the first problem ends it.
class LayoutWalker {
 public:
  // `data` is the message after its 8-byte fingerprint; reported byte
  // offsets count from the start of the datagram.
  LayoutWalker(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  std::optional<DecodeFailure> Struct(int type, const std::string& path) {
    const Type& t = lcm_schema::kTypes[type];
    // Values of this struct's integer fields, for the arrays they size.
    std::vector<int64_t> values(static_cast<size_t>(t.num_fields), 0);
    for (int i = 0; i < t.num_fields; ++i) {
      const Field& f = t.fields[i];
      const std::string name = path.empty() ? f.name : path + "." + f.name;
      int64_t count = 1;
      for (int d = 0; d < f.num_dims; ++d) {
        const int64_t n = f.dims[d].count_field >= 0
                              ? values[static_cast<size_t>(f.dims[d].count_field)]
                              : f.dims[d].fixed;
        count *= n;  // each factor was bounded when read, so no overflow
      }
      if (auto failure = Field_(f, name, count, &values[static_cast<size_t>(i)])) return failure;
    }
    return std::nullopt;
  }

  size_t pos() const { return pos_; }

 private:
  size_t left() const { return size_ - pos_; }

  std::optional<DecodeFailure> Fail(const std::string& field, const std::string& what) const {
    return DecodeFailure{"field '" + field + "' at byte " + std::to_string(start_ + 8) + ": " +
                         what};
  }

  int64_t ReadInteger(int bytes) {
    uint64_t v = 0;
    for (int b = 0; b < bytes; ++b) v = (v << 8) | data_[pos_ + static_cast<size_t>(b)];
    pos_ += static_cast<size_t>(bytes);
    switch (bytes) {
      case 1: return static_cast<int8_t>(v);
      case 2: return static_cast<int16_t>(v);
      case 4: return static_cast<int32_t>(v);
      default: return static_cast<int64_t>(v);
    }
  }

  std::optional<DecodeFailure> Field_(const Field& f, const std::string& name, int64_t count,
                                      int64_t* value) {
    start_ = pos_;
    const TypeSizes& sizes = Sizes();
    int64_t element_min = 0;
    if (f.kind == Kind::kStruct) element_min = sizes.min[static_cast<size_t>(f.struct_type)];
    else if (f.kind == Kind::kString) element_min = 5;
    else element_min = PrimitiveSize(f.kind);
    // A claimed count whose smallest encoding does not fit is refused before
    // anything is sized by it.
    // (A zero-size element is taken as one byte, so that no count can make
    // the walk loop without consuming input.)
    element_min = std::max<int64_t>(element_min, 1);
    if (count > static_cast<int64_t>(left()) / element_min)
      return Fail(name, std::to_string(count) + " elements of at least " +
                            std::to_string(element_min) + " bytes do not fit in the " +
                            std::to_string(left()) + " bytes left");

    if (f.kind == Kind::kString) {
      for (int64_t e = 0; e < count; ++e) {
        const std::string element = f.num_dims ? name + "[" + std::to_string(e) + "]" : name;
        start_ = pos_;
        if (left() < 4) return Fail(element, "truncated before its length");
        const int64_t length = ReadInteger(4);
        if (length < 1)
          return Fail(element, "string length " + std::to_string(length) +
                                   " (an LCM string holds at least its NUL)");
        if (length > static_cast<int64_t>(left()))
          return Fail(element, "string length " + std::to_string(length) + " is more than the " +
                                   std::to_string(left()) + " bytes left");
        // lcm-gen encodes a string up to its first NUL but sizes it by
        // size(): one NUL inside makes every message that repeats it (a
        // reply echoes the sender) encode short, with stale bytes after.
        const uint8_t* text = data_ + pos_;
        const size_t chars = static_cast<size_t>(length) - 1;
        if (text[chars] != 0)
          return Fail(element, "string of length " + std::to_string(length) +
                                   " does not end with a NUL");
        if (const void* nul = std::memchr(text, 0, chars))
          return Fail(element, "string of length " + std::to_string(length) +
                                   " has a NUL at character " +
                                   std::to_string(static_cast<const uint8_t*>(nul) - text));
        pos_ += static_cast<size_t>(length);
      }
      return std::nullopt;
    }
    if (f.kind == Kind::kStruct) {
      const int64_t fixed = sizes.fixed[static_cast<size_t>(f.struct_type)];
      if (fixed != kUnknownSize) {
        // Fits: checked above with min == fixed.
        pos_ += static_cast<size_t>(count * fixed);
        return std::nullopt;
      }
      for (int64_t e = 0; e < count; ++e) {
        const std::string element = f.num_dims ? name + "[" + std::to_string(e) + "]" : name;
        if (auto failure = Struct(f.struct_type, element)) return failure;
      }
      return std::nullopt;
    }
    const int bytes = PrimitiveSize(f.kind);
    if (f.num_dims == 0 && f.is_count) {
      if (left() < static_cast<size_t>(bytes)) return Fail(name, "truncated");
      *value = ReadInteger(bytes);
      if (*value < 0)
        return Fail(name, "count " + std::to_string(*value) + " is negative");
      if (f.max_count >= 0 && *value > f.max_count)
        return Fail(name, "count " + std::to_string(*value) + " is beyond the bound of " +
                              std::to_string(f.max_count) + " stated in its .lcm file");
      return std::nullopt;
    }
    // Other primitives (and arrays of them): the fit check above covers them.
    pos_ += static_cast<size_t>(count * bytes);
    return std::nullopt;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  size_t start_ = 0;  // where the field (or array element) being checked begins
};

std::string Hex(uint64_t v) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%016" PRIx64, v);
  return text;
}

}  // namespace

std::optional<DecodeFailure> CheckLcmLayout(const char* type_name, int64_t hash, const void* data,
                                            size_t size) {
  const int type = FindType(type_name);
  if (type < 0) return DecodeFailure{std::string("no layout for type '") + type_name + "'"};
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (size < 8)
    return DecodeFailure{"only " + std::to_string(size) + " bytes: too short for a fingerprint"};
  uint64_t fingerprint = 0;
  for (int b = 0; b < 8; ++b) fingerprint = (fingerprint << 8) | bytes[b];
  if (fingerprint != static_cast<uint64_t>(hash))
    return DecodeFailure{"fingerprint " + Hex(fingerprint) + " is not " + type_name + "'s (" +
                         Hex(static_cast<uint64_t>(hash)) + "): another type or version"};
  LayoutWalker walker(bytes + 8, size - 8);
  if (auto failure = walker.Struct(type, "")) return failure;
  if (walker.pos() != size - 8)
    return DecodeFailure{std::to_string(size - 8 - walker.pos()) + " bytes follow the message"};
  return std::nullopt;
}

std::string DescribeRefusal(const std::string& channel, const char* type_name, size_t size,
                            const DecodeFailure& failure) {
  return channel + ": " + std::to_string(size) + " bytes refused as simpartner." + type_name +
         ": " + failure.reason;
}

bool BadMessageCounter::Count(const std::string& channel, const std::string& description) {
  const uint64_t n = ++counts_[channel];
  ++total_;
  last_ = description;
  return n == 1 || n % kPrintEvery == 0;
}

std::optional<std::string> BadMessageCounter::CountSignatureRefusal(
    const std::string& channel, const std::string& description,
    RateLimitedLog::Clock::time_point now) {
  Count(channel, description);
  return signature_lines_.Pass("signature", description, now);
}

uint64_t BadMessageCounter::count(const std::string& channel) const {
  auto it = counts_.find(channel);
  return it == counts_.end() ? 0 : it->second;
}

std::string BadMessageCounter::Summary() const {
  std::string out;
  for (const auto& [channel, n] : counts_) {
    if (!out.empty()) out += ", ";
    out += channel + " " + std::to_string(n);
  }
  return out;
}

std::optional<size_t> OpenFromBus(const std::string& channel, const void* data, size_t size,
                                  BusSigning* signing, BadMessageCounter* counter,
                                  std::string* refusal, bool* print, SigningMismatch* mismatch) {
  const BusSigning::Opened opened = OpenMessage(signing, channel, data, size);
  if (mismatch != nullptr) mismatch->Note(signing != nullptr, data, size, opened);
  if (opened.refusal.empty()) return opened.size;
  *refusal = DescribeSignatureRefusal(channel, size, opened.refusal);
  bool should_print = true;
  if (counter != nullptr) {
    const auto line =
        counter->CountSignatureRefusal(channel, *refusal, RateLimitedLog::Clock::now());
    should_print = line.has_value();
    if (line) *refusal = *line;
  }
  if (print) *print = should_print;
  return std::nullopt;
}

std::string DescribeSignatureRefusal(const std::string& channel, size_t size,
                                     const std::string& reason) {
  return channel + ": " + std::to_string(size) + " bytes refused: " + reason;
}

}  // namespace simpartner
