// BusSender: the sim's sending thread. What a receiver must be able to rely
// on: every message arrives, in the order handed over across channels,
// signed when a key is set, and none is left behind at Flush or at the
// end.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/bus_signing.h"
#include "simpartner/channels.h"
#include "simpartner/sim/bus_sender.h"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner::sim {
namespace {

// Every message heard, as (channel, step), from one in-process bus.
struct Heard {
  explicit Heard(lcm::LCM* lcm, BusSigning* signing = nullptr) : signing_(signing) {
    for (const char* channel : {channels::kState, channels::kStatus})
      lcm->subscribe(channel, &Heard::On, this)->setQueueCapacity(1 << 20);
  }
  void On(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
    size_t size = buffer->data_size;
    if (signing_ != nullptr) {
      const BusSigning::Opened opened =
          signing_->Open(channel, buffer->data, buffer->data_size, WallMicrosNow());
      if (!opened.refusal.empty()) {
        refusals.push_back(opened.refusal);
        return;
      }
      size = opened.size;
    }
    int64_t step = -1;
    if (channel == channels::kState) {
      state_t state;
      if (state.decode(buffer->data, 0, static_cast<int>(size)) > 0) step = state.step;
    } else {
      status_t status;
      if (status.decode(buffer->data, 0, static_cast<int>(size)) > 0) step = status.step;
    }
    messages.emplace_back(channel, step);
  }
  static int64_t WallMicrosNow() {
    return std::chrono::duration_cast<std::chrono::microseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
  }
  BusSigning* signing_;
  std::vector<std::pair<std::string, int64_t>> messages;
  std::vector<std::string> refusals;
};

void HandleAll(lcm::LCM* lcm) {
  while (lcm->handleTimeout(0) > 0) {
  }
}

// Alternating channels, numbered: a state then a status per step.
void SendSteps(BusSender* sender, int steps) {
  for (int k = 0; k < steps; ++k) {
    state_t state{};
    state.step = k;
    sender->Send(channels::kState, std::move(state));
    status_t status{};
    status.step = k;
    sender->Send(channels::kStatus, std::move(status));
  }
}

void ExpectInOrder(const Heard& heard, int steps) {
  ASSERT_EQ(heard.messages.size(), static_cast<size_t>(2 * steps));
  for (int k = 0; k < steps; ++k) {
    const size_t i = 2 * static_cast<size_t>(k);
    EXPECT_EQ(heard.messages[i], std::make_pair(std::string(channels::kState), int64_t{k})) << i;
    EXPECT_EQ(heard.messages[i + 1], std::make_pair(std::string(channels::kStatus), int64_t{k}))
        << i + 1;
    if (::testing::Test::HasFailure()) return;
  }
}

TEST(BusSender, SendsEverythingInOrderAcrossChannelsAtFlush) {
  lcm::LCM lcm("memq://");
  Heard heard(&lcm);
  BusSender sender(&lcm, nullptr);
  // More than the queue holds: Send waits, never drops.
  const int steps = static_cast<int>(BusSender::kMaxQueuedMessages);
  SendSteps(&sender, steps);
  sender.Flush();
  HandleAll(&lcm);
  ExpectInOrder(heard, steps);
  EXPECT_TRUE(sender.TakeOutcomes().empty()) << "memq sends do not fail";
}

TEST(BusSender, SendsWhatIsQueuedWhenDestroyed) {
  lcm::LCM lcm("memq://");
  Heard heard(&lcm);
  {
    BusSender sender(&lcm, nullptr);
    SendSteps(&sender, 500);
  }
  HandleAll(&lcm);
  ExpectInOrder(heard, 500);
}

TEST(BusSender, ASendToAnIdleSenderGoesOutWithoutFlushOrKick) {
  lcm::LCM lcm("memq://");
  Heard heard(&lcm);
  BusSender sender(&lcm, nullptr);
  for (int round = 0; round < 3; ++round) {
    // Long enough for the sending thread to have gone to sleep.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    status_t status{};
    status.step = round;
    sender.Send(channels::kStatus, std::move(status));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (heard.messages.size() < static_cast<size_t>(round + 1) &&
           std::chrono::steady_clock::now() < deadline)
      lcm.handleTimeout(10);
    ASSERT_EQ(heard.messages.size(), static_cast<size_t>(round + 1)) << "round " << round;
  }
}

TEST(BusSender, KeepsSendingAfterAFlushWithNothingQueued) {
  lcm::LCM lcm("memq://");
  Heard heard(&lcm);
  BusSender sender(&lcm, nullptr);
  for (int round = 0; round < 3; ++round) {
    // Flushes that find nothing to send wake the sending thread with
    // nothing: it must go back to waiting, not end.
    sender.Flush();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    sender.Flush();
    status_t status{};
    status.step = round;
    sender.Send(channels::kStatus, std::move(status));
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (heard.messages.size() < static_cast<size_t>(round + 1) &&
           std::chrono::steady_clock::now() < deadline)
      lcm.handleTimeout(10);
    ASSERT_EQ(heard.messages.size(), static_cast<size_t>(round + 1)) << "round " << round;
  }
}

TEST(BusSender, SignsEachMessageInOrderForAReaderWithTheKey) {
  BusSigning::Key key{};
  key[0] = 7;
  BusSigning signer(key), reader(key), stranger(BusSigning::Key{});
  lcm::LCM lcm("memq://");
  Heard heard(&lcm, &reader);
  BusSender sender(&lcm, &signer);
  SendSteps(&sender, 300);
  sender.Flush();
  HandleAll(&lcm);
  EXPECT_TRUE(heard.refusals.empty()) << heard.refusals.front();
  ExpectInOrder(heard, 300);

  // The same messages under another key are refused, every one.
  lcm::LCM other("memq://");
  Heard foreign(&other, &stranger);
  BusSender other_sender(&other, &signer);
  SendSteps(&other_sender, 10);
  other_sender.Flush();
  HandleAll(&other);
  EXPECT_EQ(foreign.refusals.size(), 20u);
  EXPECT_TRUE(foreign.messages.empty());
}

}  // namespace
}  // namespace simpartner::sim
