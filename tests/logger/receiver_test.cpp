// The receive side on memq:// (one process): what reaches the queue, what
// waits for its model, and every kind of bad message counted per channel,
// reported with the channel and never queued.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "simpartner/channels.h"
#include "simpartner/command_t.hpp"
#include "simpartner/logger/logger.h"
#include "simpartner/logger/receiver.h"
#include "simpartner/model_request_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner::logger {
namespace {

model_t TwoBodyModel(int64_t simulation_id) {
  model_t m{};
  m.simulation_id = simulation_id;
  m.host = "testhost";
  m.world_file = "w.xml";
  m.world_name = "W";
  m.step_size = 0.001;
  m.state_every = 1;
  m.gravity[1] = -9.81;
  robot_t r{};
  r.name = "Bot";
  m.robots = {r};
  m.num_robots = 1;
  for (int i = 0; i < 2; ++i) {
    body_t b{};
    b.id = i;
    b.name = i == 0 ? "Base" : "Arm";
    b.robot = 0;
    b.mass = 1;
    b.initial_orientation[0] = 1;
    m.bodies.push_back(b);
  }
  m.num_bodies = 2;
  joint_t j{};
  j.name = "Shoulder";
  j.robot = 0;
  j.kind = joint_t::KIND_HINGE;
  j.body1 = 1;
  j.body2 = 0;
  j.num_axes = 1;
  j.lo_stop[0] = -INFINITY;
  j.hi_stop[0] = INFINITY;
  m.joints = {j};
  m.num_joints = 1;
  return m;
}

state_t State(int64_t simulation_id, int64_t step, int bodies = 2, int joints = 1) {
  state_t s{};
  s.simulation_id = simulation_id;
  s.step = step;
  s.sim_time = step * 0.001;
  s.bodies.resize(static_cast<size_t>(bodies));
  for (body_state_t& b : s.bodies) b.orientation[0] = 1.0;
  s.num_bodies = bodies;
  s.joints.resize(static_cast<size_t>(joints));
  s.num_joints = joints;
  return s;
}

class ReceiverTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("sp_receiver_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    spool_ = std::make_unique<Spool>(dir_.string(), 1 << 20, [](const std::string&) {});
    queue_ = std::make_unique<RecordQueue>(64 << 20, spool_.get());
    lcm_.subscribe(channels::kModelRequest, &ReceiverTest::OnRequest, this);
  }
  void TearDown() override {
    receiver_.reset();
    queue_.reset();
    spool_.reset();
    std::filesystem::remove_all(dir_);
  }
  void Start(int interval = 1) {
    ReceiverOptions options;
    options.log_interval = interval;
    options.sender = "test";
    receiver_ = std::make_unique<Receiver>(&lcm_, queue_.get(), options, &reporter_);
  }
  template <class M>
  void Publish(const char* channel, const M& message) {
    lcm_.publish(channel, &message);
    Drain();
  }
  void PublishRaw(const char* channel, const std::vector<uint8_t>& bytes) {
    lcm_.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
    Drain();
  }
  void Drain() {
    while (lcm_.handleTimeout(0) > 0) {
    }
  }
  std::vector<Record> Queued() {
    std::vector<Record> all;
    while (true) {
      Batch b = queue_->Take(1000, 1 << 30, std::chrono::milliseconds(0));
      if (b.empty()) break;
      for (Record& r : b.records) all.push_back(std::move(r));
      queue_->Commit(b);
    }
    return all;
  }
  static int64_t StepOf(const Record& r) {
    state_t s;
    EXPECT_GE(s.decode(r.payload.data(), 0, static_cast<int>(r.payload.size())), 0);
    return s.step;
  }
  void OnRequest(const lcm::ReceiveBuffer*, const std::string&, const model_request_t* r) {
    requests_.push_back(r->sender);
  }

  std::filesystem::path dir_;
  lcm::LCM lcm_{"memq://"};
  std::ostringstream out_;
  Reporter reporter_{&out_, "logger", std::chrono::seconds(0)};
  std::unique_ptr<Spool> spool_;
  std::unique_ptr<RecordQueue> queue_;
  std::unique_ptr<Receiver> receiver_;
  std::vector<std::string> requests_;
};

TEST_F(ReceiverTest, ModelThenStatesAreQueuedInOrder) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  for (int step = 1; step <= 3; ++step) Publish(channels::kState, State(5, step));
  Publish(channels::kModel, TwoBodyModel(5));  // announced again: not queued twice
  const std::vector<Record> q = Queued();
  ASSERT_EQ(q.size(), 4u);
  EXPECT_EQ(q[0].kind, RecordKind::kModel);
  for (int i = 1; i <= 3; ++i) {
    EXPECT_EQ(q[i].kind, RecordKind::kState);
    EXPECT_EQ(q[i].simulation_id, 5);
    EXPECT_EQ(StepOf(q[i]), i);
  }
  EXPECT_EQ(receiver_->Stats().BadMessages(), 0u);
}

TEST_F(ReceiverTest, StatesBeforeTheModelWaitAndAskForIt) {
  Start();
  Publish(channels::kState, State(9, 1));
  Publish(channels::kState, State(9, 2));
  ASSERT_FALSE(requests_.empty());
  EXPECT_EQ(requests_.back(), "test");
  EXPECT_TRUE(Queued().empty());
  EXPECT_EQ(receiver_->Stats().waiting, 2u);
  Publish(channels::kModel, TwoBodyModel(9));
  const std::vector<Record> q = Queued();
  ASSERT_EQ(q.size(), 3u);
  EXPECT_EQ(q[0].kind, RecordKind::kModel);
  EXPECT_EQ(StepOf(q[1]), 1);
  EXPECT_EQ(StepOf(q[2]), 2);
  EXPECT_EQ(receiver_->Stats().waiting, 0u);
}

TEST_F(ReceiverTest, LogIntervalKeepsEveryNthStep) {
  Start(10);
  Publish(channels::kModel, TwoBodyModel(5));
  for (int step = 1; step <= 35; ++step) Publish(channels::kState, State(5, step));
  std::vector<int64_t> steps;
  for (const Record& r : Queued())
    if (r.kind == RecordKind::kState) steps.push_back(StepOf(r));
  EXPECT_EQ(steps, (std::vector<int64_t>{10, 20, 30}));
  EXPECT_EQ(receiver_->Stats().states_skipped, 32u);
}

TEST_F(ReceiverTest, MalformedMessagesAreCountedReportedAndNeverQueued) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  Queued();
  PublishRaw(channels::kState, {1, 2, 3, 4, 5, 6, 7});  // garbage
  status_t status{};
  Publish(channels::kState, status);  // a foreign type on SIM_STATE
  const state_t good = State(5, 1);
  std::vector<uint8_t> bytes(static_cast<size_t>(good.getEncodedSize()));
  good.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  PublishRaw(channels::kState, std::vector<uint8_t>(bytes.begin(), bytes.end() - 9));  // truncated
  std::vector<uint8_t> padded = bytes;
  padded.push_back(0);
  PublishRaw(channels::kState, padded);  // a byte too many
  PublishRaw(channels::kModel, {9, 9});  // garbage model

  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.channels.at(channels::kState).malformed, 4u);
  EXPECT_EQ(stats.channels.at(channels::kState).received, 4u);
  EXPECT_EQ(stats.channels.at(channels::kModel).malformed, 1u);
  EXPECT_TRUE(Queued().empty());
  const std::string text = out_.str();
  EXPECT_NE(text.find("SIM_STATE: message of 7 bytes is not a simpartner.state_t"), std::string::npos)
      << text;
  EXPECT_NE(text.find("SIM_MODEL: message of 2 bytes is not a simpartner.model_t"), std::string::npos)
      << text;
  EXPECT_NE(text.find("not written (1 malformed so far)"), std::string::npos) << text;
}

TEST_F(ReceiverTest, MessagesThatDoNotFitTheModelAreInvalid) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  Queued();
  Publish(channels::kState, State(5, 1, 3, 1));  // a body too many
  state_t nan_state = State(5, 2);
  nan_state.bodies[1].position[2] = NAN;
  Publish(channels::kState, nan_state);
  state_t zero_quaternion = State(5, 3);
  zero_quaternion.bodies[0].orientation[0] = 0;
  Publish(channels::kState, zero_quaternion);
  model_t bad = TwoBodyModel(6);
  bad.joints[0].body1 = 7;
  Publish(channels::kModel, bad);
  model_t bad_text = TwoBodyModel(8);
  bad_text.bodies[0].name = std::string("\xff\xfe", 2);
  Publish(channels::kModel, bad_text);
  sensor_reading_t reading{};
  reading.simulation_id = 5;
  reading.sensor = 3;  // the model has no sensors
  Publish(channels::kSensor, reading);

  EXPECT_TRUE(Queued().empty());
  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.channels.at(channels::kState).invalid, 3u);
  EXPECT_EQ(stats.channels.at(channels::kModel).invalid, 2u);
  EXPECT_EQ(stats.channels.at(channels::kSensor).invalid, 1u);
  const std::string text = out_.str();
  EXPECT_NE(text.find("SIM_STATE: num_bodies = 3 but the model of simulation 5 has 2"),
            std::string::npos) << text;
  EXPECT_NE(text.find("bodies[1].position[2] = nan"), std::string::npos) << text;
  EXPECT_NE(text.find("joints[0].body1 = 7 (no such body)"), std::string::npos) << text;
  EXPECT_NE(text.find("bodies[0].name is not valid UTF-8"), std::string::npos) << text;
  EXPECT_NE(text.find("SIM_SENSOR: sensor = 3 but the model of simulation 5 has 0 sensors"),
            std::string::npos) << text;
}

TEST_F(ReceiverTest, StopStatusEndsTheSimulationAndCommandsFollowTheCurrentOne) {
  Start();
  command_t early{};
  early.sender = "teleop";
  Publish(channels::kCommand, early);  // before any model: waits for the first
  Publish(channels::kModel, TwoBodyModel(5));
  Publish(channels::kModel, TwoBodyModel(6));  // the sim restarted
  command_t late{};
  late.sender = "teleop";
  Publish(channels::kCommand, late);
  status_t stopped{};
  stopped.simulation_id = 6;
  stopped.run_state = status_t::RUN_STOPPED;
  stopped.step = 42;
  Publish(channels::kStatus, stopped);
  Publish(channels::kStatus, stopped);  // once is enough
  const std::vector<Record> q = Queued();
  ASSERT_EQ(q.size(), 5u);
  EXPECT_EQ(q[0].kind, RecordKind::kModel);
  EXPECT_EQ(q[1].kind, RecordKind::kCommand);
  EXPECT_EQ(q[1].simulation_id, 5);
  EXPECT_EQ(q[2].kind, RecordKind::kModel);
  EXPECT_EQ(q[2].simulation_id, 6);
  EXPECT_EQ(q[3].kind, RecordKind::kCommand);
  EXPECT_EQ(q[3].simulation_id, 6);
  EXPECT_EQ(q[4].kind, RecordKind::kSimulationEnded);
  EXPECT_EQ(ReadEnded(q[4]).last_step, 42);
}

TEST(ReceiverUrlTest, ReceiveBufferIsAddedToUdpmUrls) {
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667?ttl=0"),
            "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667"),
            "udpm://239.255.76.67:7667?recv_buf_size=4194304");
  EXPECT_EQ(WithReceiveBuffer("udpm://x:1?recv_buf_size=100"), "udpm://x:1?recv_buf_size=100");
  EXPECT_EQ(WithReceiveBuffer("memq://"), "memq://");
}

TEST(FitsTextTest, Utf8AndLength) {
  EXPECT_TRUE(FitsText("Wheel1", 255));
  EXPECT_TRUE(FitsText("Pyörä \xe2\x82\xac \xf0\x9f\x98\x80", 255));
  EXPECT_FALSE(FitsText(std::string(256, 'a'), 255));
  EXPECT_FALSE(FitsText("\xc3", 255));              // cut short
  EXPECT_FALSE(FitsText("\xc0\xaf", 255));          // overlong
  EXPECT_FALSE(FitsText("\xed\xa0\x80", 255));      // surrogate
  EXPECT_FALSE(FitsText(std::string("a\0b", 3), 255));
}

}  // namespace
}  // namespace simpartner::logger
