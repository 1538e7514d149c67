// Tokens that only their holder can present: 128 bits from the operating
// system's CSPRNG (OpenSSL's RAND_bytes), written as 32 hex digits, and
// compared in constant time so that timing tells a guesser nothing.
#pragma once

#include <string>

namespace simpartner {

// A new token; throws std::runtime_error when no random bytes are to be had.
std::string RandomToken();

// Whether `presented` is `expected`, in time that does not depend on where
// they differ.
bool SameToken(const std::string& presented, const std::string& expected);

}  // namespace simpartner
