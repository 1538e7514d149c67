// Tokens that only their holder can present: 128 bits (or as many as
// asked) from the operating system's CSPRNG (OpenSSL's RAND_bytes),
// written as hex digits, and compared in constant time so that timing
// tells a guesser nothing.
#pragma once

#include <cstddef>
#include <string>

namespace simpartner {

// A new token of `bytes` random bytes as 2 * `bytes` hex digits; throws
// std::runtime_error when no random bytes are to be had.
std::string RandomToken(size_t bytes = 16);

// Whether `presented` is `expected`, in time that does not depend on where
// they differ.
bool SameToken(const std::string& presented, const std::string& expected);

}  // namespace simpartner
