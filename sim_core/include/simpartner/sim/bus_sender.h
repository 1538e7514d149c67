// The sim's messages go out on a thread of their own, so a step does not
// wait for signing and the kernel's sendto (about 6 us of a 9 KB SIM_STATE
// on loopback multicast, 40 % of a gen1 MuJoCo step).
//
// The step thread encodes a message into a buffer the sender recycles (no
// allocation once warm); the sending thread signs it (when a key is set)
// and publishes it, in the order handed over, so every receiver sees the same sequence as from a synchronous
// sender (the replies and readings of a step before its state). Nothing is
// dropped: kMaxQueuedMessages waiting make the next Send wait until the
// queue drains. How each send went comes back through TakeOutcomes, for
// the node to report on its own thread.
//
// Waking a thread on the other core costs the waker a few microseconds on
// a virtual machine (an inter-processor interrupt), as much as the send
// it saves. So a Send wakes the sending thread only when it sleeps with
// nothing to do; while messages keep coming it polls every kPollPeriod,
// and the stepping thread wakes it (Kick) before it waits itself: at real
// time and in lock-step nothing waits for a poll.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/bus_signing.h"

namespace simpartner::sim {

class BusSender {
 public:
  // With this many messages waiting to be sent, Send blocks (4,096 gen4
  // states are 37 MB).
  static constexpr size_t kMaxQueuedMessages = 4096;
  // While busy, the sending thread looks this often; with kWakeAt waiting
  // a Send wakes it at once.
  static constexpr std::chrono::microseconds kPollPeriod{200};
  static constexpr size_t kWakeAt = 256;

  // `lcm` (good) and `signing` (may be null: unsigned) outlive the sender.
  BusSender(lcm::LCM* lcm, BusSigning* signing);
  // Sends what is queued, then stops the thread.
  ~BusSender();
  BusSender(const BusSender&) = delete;
  BusSender& operator=(const BusSender&) = delete;

  // Encodes `message` (an LCM type) and queues it for `channel`.
  template <class T>
  void Send(const char* channel, const T& message) {
    std::vector<uint8_t> bytes = TakeSpare();
    bytes.resize(static_cast<size_t>(message.getEncodedSize()));
    message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    Queue(channel, std::move(bytes));
  }
  // Sends what is queued now, without waiting for it to go: for a
  // thread about to wait for something else.
  void Kick();
  // Returns once everything queued before the call has been sent.
  void Flush();

  // A failed send, or the first send that worked after failures.
  struct Outcome {
    std::string channel;
    bool sent = false;
    std::string error;  // strerror of the failure
  };
  // Outcomes since the last call, in the order of the sends; sends that
  // worked while nothing was failing are not listed.
  std::vector<Outcome> TakeOutcomes();

 private:
  struct Message {
    const char* channel;  // one of channels.h's constants
    std::vector<uint8_t> bytes;
  };
  // A sent message's buffer, or an empty one.
  std::vector<uint8_t> TakeSpare();
  void Queue(const char* channel, std::vector<uint8_t> bytes);
  void SendAll();  // the sending thread
  // Waits for something to send (polling when `sent_before`); false on
  // stop with nothing queued.
  bool WaitForWork(std::unique_lock<std::mutex>* lock, bool sent_before);
  // Wakes the sending thread; unlocks `lock`.
  void Wake(std::unique_lock<std::mutex>* lock);
  void Publish(const Message& message);

  lcm::LCM* lcm_;
  BusSigning* signing_;
  std::mutex mutex_;
  std::condition_variable queued_;   // a message, or stop
  std::condition_variable drained_;  // room in the queue, or a message sent
  std::deque<Message> queue_;
  std::vector<std::vector<uint8_t>> spares_;  // sent messages' buffers
  static constexpr size_t kMaxSpares = 64;
  uint64_t messages_queued_ = 0;
  uint64_t messages_done_ = 0;
  bool stop_ = false;
  bool waiting_ = false;   // the sending thread waits (polling or not)
  bool sleeping_ = false;  // ... and will not look until woken
  bool wake_ = false;      // look now
  bool failing_ = false;  // the last send failed (sending thread only)
  std::vector<Outcome> outcomes_;
  std::thread thread_;  // last: starts once the rest is built
};

}  // namespace simpartner::sim
