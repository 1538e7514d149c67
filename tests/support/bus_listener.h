// The test's side of the bus: typed subscriptions whose messages are
// opened and decoded as every process does it (simpartner/bus_decode.h:
// the signature checked with the tests' key, unless on an UnsignedBus;
// what is refused is counted, never handed on), kept or passed to a handler, and
// Until(condition, seconds) to receive while waiting. A test derives its
// own listener from it for the figures it follows (the newest step, the
// states by step ...).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "signed_publisher.h"
#include "simpartner/bus_decode.h"

namespace simpartner::test_support {

class BusListener {
 public:
  // Messages a subscription holds while the test is not receiving (LCM
  // drops what comes beyond): 100 s of states at 1 kHz.
  static constexpr int kQueueCapacity = 100000;

  // Opens `url` and its receiving socket at once: in the caller's network
  // namespace (tests/support/netns.h), and hearing from now on. Throws
  // std::runtime_error naming the URL when LCM cannot open it.
  explicit BusListener(const std::string& url);
  BusListener(const BusListener&) = delete;
  BusListener& operator=(const BusListener&) = delete;

  // Every message of type T on `channel`, decoded, to `on_message`.
  template <class T>
  void Subscribe(const std::string& channel, std::function<void(const T&)> on_message,
                 int queue_capacity = kQueueCapacity) {
    Listen(
        channel,
        [this, on = std::move(on_message)](const lcm::ReceiveBuffer* buffer, const std::string& name) {
          T message;
          if (!DecodeSigned(name, buffer->data, buffer->data_size, signer(), &message, &refused_))
            on(message);
        },
        queue_capacity);
  }
  // Every message of type T on `channel`, appended to *all.
  template <class T>
  void Keep(const std::string& channel, std::vector<T>* all, int queue_capacity = kQueueCapacity) {
    Subscribe<T>(channel, [all](const T& message) { all->push_back(message); }, queue_capacity);
  }
  // The newest message of type T on `channel` in *latest.
  template <class T>
  void KeepLatest(const std::string& channel, T* latest, int queue_capacity = kQueueCapacity) {
    Subscribe<T>(channel, [latest](const T& message) { *latest = message; }, queue_capacity);
  }

  // Receives until condition() holds or `seconds` have passed; returns
  // condition(). The condition is looked at once per batch of the messages
  // waiting (at most kBatchSeconds of receiving), not after each: a costly
  // one (a database query, a log read) would otherwise let the queue grow
  // faster than it drains.
  bool Until(const std::function<bool()>& condition, double seconds);
  // Receives for `seconds`.
  void Pump(double seconds);
  // Receives until the file at `path` (a process's log) holds `text`,
  // reading it every 50 ms; false when `seconds` passed first.
  bool UntilFileHolds(const std::filesystem::path& path, const std::string& text, double seconds);

  // The test's messages, on the same bus, signed as a process signs
  // (signed_publisher.h).
  template <class T>
  int Publish(const std::string& channel, const T& message) {
    return publisher_.Publish(&lcm_, channel, message);
  }
  int PublishBytes(const std::string& channel, const void* data, size_t size) {
    return publisher_.PublishBytes(&lcm_, channel, data, size);
  }
  BusSigning* signer() { return publisher_.signer(); }
  // For what the test sends unsigned, as a forger without the key would.
  lcm::LCM& lcm() { return lcm_; }
  // The messages refused on this listener's channels, per channel.
  const BadMessageCounter& refused() const { return refused_; }

 private:
  using RawHandler = std::function<void(const lcm::ReceiveBuffer*, const std::string&)>;
  // LCM 1.3 takes a member function, not a std::function.
  struct Subscription {
    RawHandler handler;
    void Receive(const lcm::ReceiveBuffer* buffer, const std::string& channel) { handler(buffer, channel); }
  };
  void Listen(const std::string& channel, RawHandler handler, int queue_capacity);
  // Waits up to 10 ms for a message, then receives every message waiting,
  // for at most kBatchSeconds or until `end`.
  void ReceiveWaiting(std::chrono::steady_clock::time_point end);
  static constexpr double kBatchSeconds = 0.1;

  lcm::LCM lcm_;
  SignedPublisher publisher_;
  BadMessageCounter refused_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
};

}  // namespace simpartner::test_support
