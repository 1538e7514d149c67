// What a test sends on the bus, signed as every process signs
// (simpartner/bus_signing.h): with the tests' own key, which
// tests/CMakeLists.txt names in SIMPARTNER_BUS_KEY for every test, or
// unsigned on an UnsignedBus. A forger without the key publishes on the
// lcm::LCM itself.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstddef>
#include <optional>
#include <string>

#include "simpartner/bus_signing.h"

namespace simpartner::test_support {

class SignedPublisher {
 public:
  // The key of the environment now (FromEnvironment), one link for every
  // message this publisher signs.
  SignedPublisher();

  // lcm's status: 0 when sent.
  template <class T>
  int Publish(lcm::LCM* lcm, const std::string& channel, const T& message) {
    return PublishSigned(lcm, channel, message, signer());
  }
  // `size` bytes as they are (a datagram that may not decode), signed.
  int PublishBytes(lcm::LCM* lcm, const std::string& channel, const void* data, size_t size);

  BusSigning* signer() { return signing_ ? &*signing_ : nullptr; }

 private:
  std::optional<BusSigning> signing_;
};

// SIMPARTNER_BUS_KEY=none while it lives, for the processes a test starts
// and the publishers it makes meanwhile: for what an unsigned bus does
// (followers facing a copied model, lock-step marks without their token),
// which a key would hide.
class UnsignedBus {
 public:
  UnsignedBus();
  ~UnsignedBus();
  UnsignedBus(const UnsignedBus&) = delete;
  UnsignedBus& operator=(const UnsignedBus&) = delete;

 private:
  std::optional<std::string> previous_;
};

}  // namespace simpartner::test_support
