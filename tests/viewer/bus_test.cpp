// The viewer's bus side on memq:// (one process): a drain handles every
// message that arrived and keeps the newest state, model requests go out
// when the model is missing (rate-limited), bad bytes are counted, and the
// control keys publish SIM_CONTROL.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <thread>

#include "simpartner/channels.h"
#include "simpartner/status_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/model_request_t.hpp"
#include "simpartner/viewer/bus.h"
#include "viewer_messages.h"

namespace simpartner::viewer {
namespace {

using testing::ScanFor;
using testing::StateFor;
using testing::TwoBodyModel;
using Clock = std::chrono::steady_clock;

class BusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lcm_.subscribe(channels::kModelRequest, &BusTest::OnRequest, this);
    lcm_.subscribe(channels::kControl, &BusTest::OnControl, this);
    lcm_.subscribe(channels::kCommand, &BusTest::OnCommand, this);
  }
  template <class M>
  void Publish(const char* channel, const M& message) {
    lcm_.publish(channel, &message);
  }
  void OnRequest(const lcm::ReceiveBuffer*, const std::string&, const model_request_t* r) {
    requests_.push_back(*r);
  }
  void OnControl(const lcm::ReceiveBuffer*, const std::string&, const control_t* c) {
    controls_.push_back(*c);
  }
  void OnCommand(const lcm::ReceiveBuffer*, const std::string&, const command_t* c) {
    commands_.push_back(*c);
  }

  lcm::LCM lcm_{"memq://"};
  Scene scene_;
  std::vector<std::string> reports_;
  ViewerBus bus_{&lcm_, "memq://", &scene_, [this](const std::string& m) { reports_.push_back(m); }};
  std::vector<model_request_t> requests_;
  std::vector<control_t> controls_;
  std::vector<command_t> commands_;
};

TEST_F(BusTest, AskForTheModelAtStartAndNotTooOften) {
  bus_.RequestModelIfNeeded();
  bus_.Drain(Clock::now());
  ASSERT_EQ(requests_.size(), 1u);
  EXPECT_EQ(requests_[0].sender.rfind("viewer@", 0), 0u) << requests_[0].sender;
  // States without a model want it again, but within half a second only once.
  const model_t m = TwoBodyModel(3);
  for (int step = 1; step <= 20; ++step) Publish(channels::kState, StateFor(m, step));
  bus_.Drain(Clock::now());
  EXPECT_EQ(requests_.size(), 1u);
  std::this_thread::sleep_for(std::chrono::milliseconds(550));
  Publish(channels::kState, StateFor(m, 21));
  bus_.Drain(Clock::now());
  bus_.Drain(Clock::now());  // the request itself arrives on the next drain
  EXPECT_EQ(requests_.size(), 2u);
  EXPECT_EQ(scene_.states_before_model(), 21);
}

TEST_F(BusTest, ADrainHandlesEverythingAndKeepsTheNewestState) {
  const model_t m = TwoBodyModel(3);
  lcm_.publish(channels::kModel, &m);
  for (int step = 1; step <= 500; ++step) Publish(channels::kState, StateFor(m, step));
  const int handled = bus_.Drain(Clock::now());
  EXPECT_GE(handled, 501);
  ASSERT_TRUE(scene_.has_state());
  EXPECT_EQ(scene_.state()->step, 500);
  EXPECT_EQ(scene_.states_accepted(), 500);
  // Nothing is left for the next drain.
  EXPECT_EQ(bus_.Drain(Clock::now()), 0);
}

TEST_F(BusTest, UndecodableBytesAreCountedAndReportedOnce) {
  const model_t m = TwoBodyModel(3);
  lcm_.publish(channels::kModel, &m);
  const uint8_t garbage[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  for (int i = 0; i < 3; ++i) lcm_.publish(channels::kState, garbage, sizeof garbage);
  lcm_.publish(channels::kModel, garbage, sizeof garbage);
  bus_.Drain(Clock::now());
  EXPECT_EQ(scene_.rejected(Rejection::kUndecodable), 4);
  ASSERT_EQ(reports_.size(), 1u);  // the first of the kind; later ones only counted
  EXPECT_EQ(reports_[0].rfind("SIM_STATE: 9 bytes refused as simpartner.state_t: fingerprint ", 0), 0u)
      << reports_[0];
  EXPECT_TRUE(scene_.has_model());  // the good model stays
}

// A reset: the old simulation's last status says so (RUN_RESET), then the
// new one's states and model come.
TEST_F(BusTest, ARestartedSimulationIsFollowed) {
  const model_t first = TwoBodyModel(3);
  lcm_.publish(channels::kModel, &first);
  Publish(channels::kState, StateFor(first, 10));
  bus_.Drain(Clock::now());
  status_t reset{};
  reset.simulation_id = 3;
  reset.run_state = status_t::RUN_RESET;
  lcm_.publish(channels::kStatus, &reset);
  // The new sim's states come before its model reaches us: ask for it.
  const model_t second = TwoBodyModel(4);
  Publish(channels::kState, StateFor(second, 1));
  bus_.Drain(Clock::now());
  bus_.Drain(Clock::now());
  ASSERT_FALSE(requests_.empty());
  lcm_.publish(channels::kModel, &second);
  Publish(channels::kState, StateFor(second, 2));
  bus_.Drain(Clock::now());
  EXPECT_EQ(scene_.simulation_id(), 4);
  EXPECT_EQ(scene_.state()->step, 2);
  EXPECT_EQ(scene_.rejected(Rejection::kOtherSimulation), 1);
}

TEST_F(BusTest, ControlAndScanRequestsGoOut) {
  const model_t m = TwoBodyModel(3);
  lcm_.publish(channels::kModel, &m);
  bus_.Drain(Clock::now());
  bus_.SendControl(control_t::ACTION_PAUSE);
  bus_.SendControl(control_t::ACTION_STEP, 100);
  bus_.RequestScans();
  bus_.Drain(Clock::now());
  ASSERT_EQ(controls_.size(), 2u);
  EXPECT_EQ(controls_[0].action, control_t::ACTION_PAUSE);
  EXPECT_EQ(controls_[1].action, control_t::ACTION_STEP);
  EXPECT_EQ(controls_[1].steps, 100);
  EXPECT_NE(controls_[0].request_id, controls_[1].request_id);
  ASSERT_EQ(commands_.size(), 1u);
  EXPECT_EQ(commands_[0].target, "Scanner");
  EXPECT_EQ(commands_[0].robot, "Bot");
  EXPECT_EQ(commands_[0].action, command_t::ACTION_READ);
  // A reading that comes back is kept for drawing.
  Publish(channels::kSensor, ScanFor(m, {2, 3, 4}));
  bus_.Drain(Clock::now());
  EXPECT_EQ(scene_.scans().size(), 1u);
}

TEST_F(BusTest, DrainWaitsForMessagesUntilTheDeadline) {
  const auto start = Clock::now();
  bus_.Drain(start + std::chrono::milliseconds(120));
  EXPECT_GE(Clock::now() - start, std::chrono::milliseconds(115));
}

}  // namespace
}  // namespace simpartner::viewer
