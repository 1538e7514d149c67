#include "signed_publisher.h"

#include <cstdlib>
#include <vector>

namespace simpartner::test_support {

SignedPublisher::SignedPublisher() : signing_(BusSigning::FromEnvironment({})) {}

int SignedPublisher::PublishBytes(lcm::LCM* lcm, const std::string& channel, const void* data,
                                  size_t size) {
  if (!signing_) return lcm->publish(channel, data, static_cast<unsigned>(size));
  const std::vector<uint8_t> bytes = signing_->Sign(channel, data, size);
  return lcm->publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}

UnsignedBus::UnsignedBus() {
  if (const char* value = std::getenv(kBusKeyVariable)) previous_ = value;
  ::setenv(kBusKeyVariable, kNoBusKey, 1);
}

UnsignedBus::~UnsignedBus() {
  if (previous_) ::setenv(kBusKeyVariable, previous_->c_str(), 1);
  else ::unsetenv(kBusKeyVariable);
}

}  // namespace simpartner::test_support
