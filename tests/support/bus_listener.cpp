#include "bus_listener.h"

#include <algorithm>
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

void BusListener::ReceiveWaiting(std::chrono::steady_clock::time_point end) {
  using Clock = std::chrono::steady_clock;
  if (lcm_.handleTimeout(10) <= 0) return;
  const Clock::time_point batch_end =
      std::min(end, Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                       std::chrono::duration<double>(kBatchSeconds)));
  while (Clock::now() < batch_end && lcm_.handleTimeout(0) > 0) {
  }
}

bool BusListener::Until(const std::function<bool()>& condition, double seconds) {
  const auto end = std::chrono::steady_clock::now() +
                   std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                       std::chrono::duration<double>(seconds));
  for (;;) {
    if (condition()) return true;
    if (std::chrono::steady_clock::now() >= end) return false;
    ReceiveWaiting(end);
  }
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
