#include "bus_listener.h"

#include <chrono>
#include <stdexcept>

#include "text_file.h"

namespace simpartner::test_support {

BusListener::BusListener(const std::string& url) : lcm_(url) {
  // getFileno() opens the receiving socket now rather than at the first
  // handleTimeout().
  if (!lcm_.good() || lcm_.getFileno() < 0)
    throw std::runtime_error("BusListener: LCM cannot open '" + url + "'");
}

void BusListener::Listen(const std::string& channel, RawHandler handler, int queue_capacity) {
  subscriptions_.push_back(std::make_unique<Subscription>(Subscription{std::move(handler)}));
  lcm_.subscribe(channel, &Subscription::Receive, subscriptions_.back().get())
      ->setQueueCapacity(queue_capacity);
}

bool BusListener::Until(const std::function<bool()>& condition, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!condition() && std::chrono::steady_clock::now() < end) lcm_.handleTimeout(10);
  return condition();
}

void BusListener::Pump(double seconds) {
  Until([] { return false; }, seconds);
}

bool BusListener::UntilFileHolds(const std::filesystem::path& path, const std::string& text, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (ReadText(path).find(text) == std::string::npos) {
    if (std::chrono::steady_clock::now() >= end) return false;
    Pump(0.05);
  }
  return true;
}

}  // namespace simpartner::test_support
