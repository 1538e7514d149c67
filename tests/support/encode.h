// A message as the bytes lcm-gen's encoder writes for it (what goes on the
// bus), for tests that build datagrams, compare states byte by byte or
// feed a decoder.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace simpartner::test_support {

// Throws std::logic_error when the encoder does not fill exactly the size
// it announced (a message whose counts disagree with its arrays).
template <class T>
std::vector<uint8_t> Encode(const T& message) {
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  const int written = message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  if (written != static_cast<int>(bytes.size()))
    throw std::logic_error(std::string(T::getTypeName()) + ": encode wrote " + std::to_string(written) +
                           " of " + std::to_string(bytes.size()) + " bytes");
  return bytes;
}

}  // namespace simpartner::test_support
