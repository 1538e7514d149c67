// The receive side on memq:// (one process): what reaches the queue, what
// waits for its model, and every kind of bad message counted per channel,
// reported with the channel and never queued.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <climits>
#include <map>
#include <set>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <thread>

#include "simpartner/bus_decode.h"
#include "simpartner/channels.h"
#include "simpartner/command_t.hpp"
#include "simpartner/image_t.hpp"
#include "simpartner/logger/logger.h"
#include "simpartner/logger/receiver.h"
#include "simpartner/logger/state_conflicts.h"
#include "simpartner/model_request_t.hpp"
#include "simpartner/status_t.hpp"
#include "../support/encode.h"
#include "../support/hostile_corpus.h"

namespace simpartner::logger {
namespace {

using test_support::Encode;

model_t TwoBodyModel(int64_t simulation_id) {
  model_t m{};
  m.simulation_id = simulation_id;
  m.host = "testhost";
  m.world_file = "w.xml";
  m.world_name = "W";
  m.step_size = 0.001;
  m.state_every = 1;
  m.gravity[1] = -9.81;
  m.up[1] = 1;
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
  void Start(int interval = 1, double sim_silence = 10.0, double follow_silence = 2.5,
             BusSigning* signing = nullptr) {
    ReceiverOptions options;
    options.signing = signing;
    options.log_interval = interval;
    options.sender = "test";
    options.sim_silence = sim_silence;
    options.follow_silence = follow_silence;
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
  const std::vector<uint8_t> bytes = Encode(good);
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
  // The shared decoder's description (bus_decode.h DescribeRefusal).
  EXPECT_NE(text.find("SIM_STATE: 7 bytes refused as simpartner.state_t"), std::string::npos)
      << text;
  EXPECT_NE(text.find("SIM_MODEL: 2 bytes refused as simpartner.model_t"), std::string::npos)
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
  // Wheels on soil: one naming a body the model lacks, one with a NaN slip.
  state_t no_such_wheel = State(5, 4);
  no_such_wheel.wheel_soil.resize(1);
  no_such_wheel.num_wheel_soil = 1;
  no_such_wheel.wheel_soil[0].body = 2;
  Publish(channels::kState, no_such_wheel);
  state_t nan_slip = State(5, 5);
  nan_slip.wheel_soil.resize(2);
  nan_slip.num_wheel_soil = 2;
  nan_slip.wheel_soil[1].slip = NAN;
  Publish(channels::kState, nan_slip);
  model_t bad = TwoBodyModel(6);
  bad.joints[0].body1 = 7;
  Publish(channels::kModel, bad);
  model_t bad_text = TwoBodyModel(8);
  bad_text.bodies[0].name = std::string("\xff\xfe", 2);
  Publish(channels::kModel, bad_text);
  model_t long_engine = TwoBodyModel(9);
  long_engine.engine = std::string(33, 'e');  // Simulation.engine holds 32
  Publish(channels::kModel, long_engine);
  sensor_reading_t reading{};
  reading.simulation_id = 5;
  reading.sensor = 3;  // the model has no sensors
  Publish(channels::kSensor, reading);

  EXPECT_TRUE(Queued().empty());
  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.channels.at(channels::kState).invalid, 5u);
  EXPECT_EQ(stats.channels.at(channels::kModel).invalid, 3u);
  EXPECT_EQ(stats.channels.at(channels::kSensor).invalid, 1u);
  const std::string text = out_.str();
  EXPECT_NE(text.find("SIM_STATE: num_bodies = 3 but the model of simulation 5 has 2"),
            std::string::npos) << text;
  EXPECT_NE(text.find("bodies[1].position[2] = nan"), std::string::npos) << text;
  EXPECT_NE(text.find("wheel_soil[0].body = 2 but the model of simulation 5 has 2 bodies"),
            std::string::npos) << text;
  EXPECT_NE(text.find("wheel_soil[1].slip = nan"), std::string::npos) << text;
  EXPECT_NE(text.find("joints[0].body1 = 7 (no such body)"), std::string::npos) << text;
  EXPECT_NE(text.find("bodies[0].name is not valid UTF-8"), std::string::npos) << text;
  EXPECT_NE(text.find("engine is not valid UTF-8 of at most 32 bytes (33 bytes)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("SIM_SENSOR: sensor = 3 but the model of simulation 5 has 0 sensors"),
            std::string::npos) << text;
}

// The new kinds' readings are logged like the thesis's; camera images
// (SIM_IMAGE, about 1 MB each) are not the logger's: not queued, not
// counted, not reported (docs/data.md says why, and how to record them).
TEST_F(ReceiverTest, LidarReadingsAreQueuedAndImagesIgnoredQuietly) {
  Start();
  model_t model = TwoBodyModel(5);
  for (int kind : {sensor_t::KIND_LIDAR, sensor_t::KIND_CAMERA}) {
    sensor_t s{};
    s.id = static_cast<int32_t>(model.sensors.size());
    s.name = kind == sensor_t::KIND_LIDAR ? "Lidar" : "Eye";
    s.kind = static_cast<int8_t>(kind);
    s.body = 0;
    s.joint = -1;
    s.orientation[0] = 1;
    s.rate = 10;
    s.params = kind == sensor_t::KIND_LIDAR ? std::vector<double>{5, 0.5, 2, -0.1, 0.1, 0.5, 50, 0, 0}
                                            : std::vector<double>{4, 2, 1.0, 0.1, 50, 0};
    s.num_params = static_cast<int32_t>(s.params.size());
    model.sensors.push_back(s);
  }
  model.num_sensors = 2;
  Publish(channels::kModel, model);
  Queued();
  sensor_reading_t reading{};
  reading.simulation_id = 5;
  reading.step = 1;
  reading.sensor = 0;
  reading.name = "Lidar";
  reading.kind = sensor_t::KIND_LIDAR;
  reading.values = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};  // 2 layers x 5 rays
  reading.num_values = 10;
  Publish(channels::kSensor, reading);
  image_t image{};
  image.simulation_id = 5;
  image.step = 1;
  image.camera = 1;
  image.name = "Eye";
  image.robot = "Bot";
  image.width = 4;
  image.height = 2;
  image.format = image_t::FORMAT_RGB8;
  image.data.assign(24, 100);
  image.num_bytes = 24;
  Publish(channels::kImage, image);
  PublishRaw(channels::kImage, {1, 2, 3});  // not even an image: still not the logger's

  const std::vector<Record> q = Queued();
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q[0].kind, RecordKind::kSensor);
  sensor_reading_t queued;
  ASSERT_FALSE(DecodeLcm(q[0].payload.data(), q[0].payload.size(), &queued));
  EXPECT_EQ(queued.values, reading.values);
  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.BadMessages(), 0u);
  EXPECT_EQ(stats.channels.count(channels::kImage), 0u);
  EXPECT_EQ(out_.str().find("SIM_IMAGE"), std::string::npos) << out_.str();
}

TEST_F(ReceiverTest, StopStatusEndsTheSimulationAndCommandsFollowTheCurrentOne) {
  Start();
  command_t early{};
  early.sender = "teleop";
  Publish(channels::kCommand, early);  // before any model: waits for the first
  Publish(channels::kModel, TwoBodyModel(5));
  status_t reset{};
  reset.simulation_id = 5;
  reset.run_state = status_t::RUN_RESET;
  reset.step = 10;
  Publish(channels::kStatus, reset);           // the sim was reset:
  Publish(channels::kModel, TwoBodyModel(6));  // its successor
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

// Overwrites the big-endian int32 at `offset` (LCM's encoding).
void PutInt32(std::vector<uint8_t>* bytes, size_t offset, int32_t value) {
  const uint32_t v = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) (*bytes)[offset + static_cast<size_t>(i)] = static_cast<uint8_t>(v >> (24 - 8 * i));
}

// Datagrams lcm-gen's own decoder cannot survive (a string length of 0 or
// less throws, a count of 2^31-1 allocates before it checks): the shared
// decoder refuses each, the receiver counts and describes it, and goes on
// with the valid states after it.
TEST_F(ReceiverTest, HostileLengthsAndCountsAreRefusedAndLoggingGoesOn) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  Publish(channels::kState, State(5, 1));
  // command_t: 8-byte fingerprint, utime, request_id, simulation_id, then
  // sender's length.
  command_t command{};
  command.sender = "";
  command.robot = "";
  command.target = "";
  std::vector<uint8_t> sender_zero = Encode(command);
  PutInt32(&sender_zero, 32, 0);
  PublishRaw(channels::kCommand, sender_zero);
  std::vector<uint8_t> sender_negative = Encode(command);
  PutInt32(&sender_negative, 32, -5);
  PublishRaw(channels::kCommand, sender_negative);
  // command_t num_values: after three empty strings (5 bytes each), port
  // (4), action (1) and apply_at_step (8): byte 32 + 15 + 13 = 60.
  std::vector<uint8_t> values_huge = Encode(command);
  PutInt32(&values_huge, 60, INT32_MAX);
  PublishRaw(channels::kCommand, values_huge);
  // state_t: fingerprint, utime, simulation_id, step, sim_time: num_bodies
  // at byte 40.
  std::vector<uint8_t> bodies_negative = Encode(State(5, 2));
  PutInt32(&bodies_negative, 40, -1);
  PublishRaw(channels::kState, bodies_negative);
  std::vector<uint8_t> bodies_huge = Encode(State(5, 2));
  PutInt32(&bodies_huge, 40, INT32_MAX);
  PublishRaw(channels::kState, bodies_huge);
  for (int step = 2; step <= 4; ++step) Publish(channels::kState, State(5, step));

  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.channels.at(channels::kCommand).malformed, 3u);
  EXPECT_EQ(stats.channels.at(channels::kState).malformed, 2u);
  EXPECT_EQ(stats.channels.at(channels::kState).received, 6u);
  EXPECT_EQ(stats.BadMessages(), 5u);
  std::vector<int64_t> steps;
  for (const Record& r : Queued())
    if (r.kind == RecordKind::kState) steps.push_back(StepOf(r));
  EXPECT_EQ(steps, (std::vector<int64_t>{1, 2, 3, 4}));
  const std::string text = out_.str();
  const std::string command_refused =
      "SIM_COMMAND: " + std::to_string(sender_zero.size()) + " bytes refused as simpartner.command_t";
  EXPECT_NE(text.find(command_refused + ": field 'sender' at byte 32: string length 0"),
            std::string::npos) << text;
  EXPECT_NE(text.find(command_refused + ": field 'sender' at byte 32: string length -5"),
            std::string::npos) << text;
  EXPECT_NE(text.find("field 'num_values' at byte 60: count 2147483647"), std::string::npos) << text;
  EXPECT_NE(text.find("refused as simpartner.state_t: field 'num_bodies' at byte 40: count -1 is negative"),
            std::string::npos) << text;
  EXPECT_NE(text.find("field 'num_bodies' at byte 40: count 2147483647"), std::string::npos) << text;
  EXPECT_NE(text.find("(3 malformed so far)"), std::string::npos) << text;
}

// Every datagram of the shared hostile corpus on the logger's channels,
// each followed by a valid state: every undecodable one is counted as
// malformed on its channel, nothing of them reaches the queue but what
// fits (a command with odd values is still a command seen on the bus), and
// every valid state after them is queued, in order.
TEST_F(ReceiverTest, TheHostileCorpusIsRefusedAndTheValidStatesAroundItAreKept) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  ASSERT_EQ(Queued().size(), 1u);  // the model
  const std::set<std::string> subscribed = {channels::kModel, channels::kState, channels::kSensor,
                                            channels::kCommand, channels::kCommandReply,
                                            channels::kStatus};
  std::map<std::string, uint64_t> undecodable;
  int64_t step = 0;
  Publish(channels::kState, State(5, ++step));
  for (const test_support::HostileMessage& m : test_support::HostileCorpus(5)) {
    if (subscribed.count(m.channel) == 0) continue;
    if (m.undecodable) ++undecodable[m.channel];
    PublishRaw(m.channel.c_str(), m.bytes);
    Publish(channels::kState, State(5, ++step));
  }
  ASSERT_GT(undecodable.size(), 4u) << "the corpus covers the logger's channels";
  const ReceiverStats stats = receiver_->Stats();
  for (const auto& [channel, count] : undecodable)
    EXPECT_EQ(stats.channels.at(channel).malformed, count) << channel;
  std::vector<int64_t> steps, expected;
  for (const Record& r : Queued()) {
    if (r.kind == RecordKind::kState) steps.push_back(StepOf(r));
    EXPECT_NE(r.kind, RecordKind::kModel) << "a hostile model was queued";
    EXPECT_NE(r.kind, RecordKind::kSensor) << "a hostile sensor reading was queued";
  }
  for (int64_t s = 1; s <= step; ++s) expected.push_back(s);
  EXPECT_EQ(steps, expected);
  const std::string text = out_.str();
  for (const auto& [channel, count] : undecodable)
    EXPECT_NE(text.find(channel + ": "), std::string::npos) << channel << "\n" << text;
}

// A state whose step is beyond what the sim's rate allows since the last
// one (5e8 right after 1000: 1000 x real time at 1 ms steps allows about a
// million) is refused as invalid and described; the steps after it go on.
TEST_F(ReceiverTest, AForgedStepNumberIsRefusedAndLoggingGoesOn) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  for (int step = 1; step <= 1000; ++step) Publish(channels::kState, State(5, step));
  Publish(channels::kState, State(5, 500000000));
  for (int step = 1001; step <= 1010; ++step) Publish(channels::kState, State(5, step));
  std::vector<int64_t> steps;
  for (const Record& r : Queued())
    if (r.kind == RecordKind::kState) steps.push_back(StepOf(r));
  ASSERT_EQ(steps.size(), 1010u);
  EXPECT_EQ(steps[999], 1000);
  EXPECT_EQ(steps[1000], 1001);
  EXPECT_EQ(steps.back(), 1010);
  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.channels.at(channels::kState).invalid, 1u);
  EXPECT_EQ(stats.last_step, 1010);
  const std::string text = out_.str();
  EXPECT_NE(text.find("SIM_STATE: step = 500000000 is 499999000 steps after step 1000"),
            std::string::npos) << text;
  EXPECT_NE(text.find("refused as forged or absurd"), std::string::npos) << text;
}

// The step rule at the sim's own speed (SIM_STATUS): at speed 1 a state
// 5,000 steps ahead of the last, at once, is refused (1000 x real time
// let it in, and a forged state +0.9e6 steps ahead made a 10-million-step
// gap); no gap is recorded for it, and the real steps go on.
TEST_F(ReceiverTest, AtTheSimsSpeedAStateALittleAheadIsRefused) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  status_t status{};
  status.simulation_id = 5;
  status.run_state = status_t::RUN_RUNNING;
  status.target_speed = 1;
  status.real_time_factor = 1;
  Publish(channels::kStatus, status);
  for (int step = 1; step <= 100; ++step) Publish(channels::kState, State(5, step));
  Publish(channels::kState, State(5, 5100));
  for (int step = 101; step <= 110; ++step) Publish(channels::kState, State(5, step));
  std::vector<int64_t> steps;
  for (const Record& r : Queued()) {
    EXPECT_NE(r.kind, RecordKind::kGap);
    if (r.kind == RecordKind::kState) steps.push_back(StepOf(r));
  }
  ASSERT_EQ(steps.size(), 110u);
  EXPECT_EQ(steps.back(), 110);
  EXPECT_NE(out_.str().find("step = 5100 is 5000 steps after step 100"), std::string::npos)
      << out_.str();
  EXPECT_NE(out_.str().find("more than 2 x real time allows"), std::string::npos) << out_.str();
}

// The states of one step queued, in queue order, as body 0's x (a forged
// state below says 99 there; the sim's say 0).
std::vector<double> XsOfStep(const std::vector<Record>& records, int64_t step) {
  std::vector<double> xs;
  for (const Record& r : records) {
    state_t s;
    if (r.kind != RecordKind::kState) continue;
    EXPECT_GE(s.decode(r.payload.data(), 0, static_cast<int>(r.payload.size())), 0);
    if (s.step == step) xs.push_back(s.bodies[0].position[0]);
  }
  return xs;
}

size_t Occurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

const char kConflictLine[] = "two different SIM_STATEs for one step";

// Without a key, a forged state for step 101 (x = 99) comes
// while the sim is at step 100, within the step allowance; the sim's own
// step 101 comes after it. The first stays first (the writer keeps the
// first of a step); the second, different, is a conflict, counted and
// named once with the simulation and the step.
TEST_F(ReceiverTest, AForgedStateBeforeTheRealOneIsCountedAndNamed) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  for (int step = 1; step <= 100; ++step) Publish(channels::kState, State(5, step));
  state_t forged = State(5, 101);
  forged.bodies[0].position[0] = 99;
  Publish(channels::kState, forged);
  for (int step = 101; step <= 103; ++step) Publish(channels::kState, State(5, step));
  EXPECT_EQ(XsOfStep(Queued(), 101), (std::vector<double>{99, 0}));
  EXPECT_EQ(receiver_->Stats().state_conflicts, 1u);
  EXPECT_EQ(receiver_->Stats().BadMessages(), 0u);
  const std::string text = out_.str();
  EXPECT_EQ(Occurrences(text, kConflictLine), 1u) << text;
  EXPECT_NE(text.find("bus simulation 5, step 101: two different SIM_STATEs for one step: another "
                      "sender on the bus forges this simulation's states; the first was kept; "
                      "on a signed bus (the default, not SIMPARTNER_BUS_KEY=none) forged states "
                      "are refused (docs/security.md)"),
            std::string::npos) << text;
}

// The same state twice (a retransmit, a second path), and again with only
// its publishing time changed: no conflict, nothing said.
TEST_F(ReceiverTest, AnIdenticalStateAgainIsNoConflict) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  state_t state = State(5, 1);
  state.utime = 1000;
  Publish(channels::kState, state);
  Publish(channels::kState, state);
  state.utime = 2000;
  Publish(channels::kState, state);
  EXPECT_EQ(XsOfStep(Queued(), 1).size(), 3u);
  EXPECT_EQ(receiver_->Stats().state_conflicts, 0u);
  EXPECT_EQ(out_.str().find(kConflictLine), std::string::npos) << out_.str();
}

// 50 forged states ahead (steps 101..150), then the sim's 50: 50
// conflicts, counted, in one line (the reporter here limits nothing: the
// conflicts' own limit of a line a second does).
TEST_F(ReceiverTest, ManyConflictsWithinASecondGiveOneLine) {
  Start();
  Publish(channels::kModel, TwoBodyModel(5));
  for (int step = 1; step <= 100; ++step) Publish(channels::kState, State(5, step));
  for (int step = 101; step <= 150; ++step) {
    state_t forged = State(5, step);
    forged.bodies[0].position[0] = 99;
    Publish(channels::kState, forged);
  }
  for (int step = 101; step <= 150; ++step) Publish(channels::kState, State(5, step));
  EXPECT_EQ(receiver_->Stats().state_conflicts, 50u);
  EXPECT_EQ(Occurrences(out_.str(), kConflictLine), 1u) << out_.str();
}

std::vector<uint8_t> EncodedState(int64_t step, double x) {
  state_t s = State(5, step);
  s.bodies[0].position[0] = x;
  return Encode(s);
}

// The line a second later says how many were held back since, and the
// total (the clock is the test's).
TEST(StateConflictsTest, TheNextLineASecondLaterCountsTheOnesHeldBack) {
  StateConflicts conflicts;
  const StateConflicts::Clock::time_point t0{};
  for (int step = 1; step <= 101; ++step) {
    ASSERT_FALSE(conflicts.Check(5, step, EncodedState(step, 99), t0).conflict);
  }
  int lines = 0;
  for (int step = 1; step <= 100; ++step) {
    const auto verdict =
        conflicts.Check(5, step, EncodedState(step, 0), t0 + std::chrono::milliseconds(5 * step));
    EXPECT_TRUE(verdict.conflict);
    if (verdict.line) ++lines;
  }
  EXPECT_EQ(lines, 1);
  const auto later =
      conflicts.Check(5, 101, EncodedState(101, 0), t0 + std::chrono::milliseconds(1500));
  ASSERT_TRUE(later.line);
  EXPECT_NE(later.line->find("step 101: two different SIM_STATEs"), std::string::npos) << *later.line;
  EXPECT_NE(later.line->find("101 conflicting states so far (and 99 more conflicting states since "
                             "the last report)"),
            std::string::npos) << *later.line;
  EXPECT_EQ(conflicts.count(), 101u);
}

// The memory keeps each simulation's highest 4096 steps: a forged state
// 5,000 steps ahead is still remembered when the sim's own state of that
// step comes, after 5,000 others; a step below the window is forgotten.
TEST(StateConflictsTest, AStateFarAheadIsRememberedUntilItsStepComes) {
  StateConflicts conflicts;
  const StateConflicts::Clock::time_point t0{};
  EXPECT_FALSE(conflicts.Check(5, 5001, EncodedState(5001, 99), t0).conflict);
  for (int step = 1; step <= 5000; ++step) conflicts.Check(5, step, EncodedState(step, 0), t0);
  EXPECT_TRUE(conflicts.Check(5, 5001, EncodedState(5001, 0), t0).conflict);
  // The highest 4096 remain (906..5001): step 1 is gone, so a different
  // state of it is not seen as a conflict.
  EXPECT_FALSE(conflicts.Check(5, 1, EncodedState(1, 99), t0).conflict);
  EXPECT_TRUE(conflicts.Check(5, 4999, EncodedState(4999, 99), t0).conflict);
}

TEST(StepAllowanceTest, TheSimsSpeedSetsTheFactor) {
  EXPECT_EQ(SpeedAllowance(1, 0.98), 2);
  EXPECT_EQ(SpeedAllowance(5, 4.9), 10);
  EXPECT_EQ(SpeedAllowance(0.1, 3), 6);      // measured above the target: a burst
  EXPECT_EQ(SpeedAllowance(0, 1.35), 10);    // as fast as possible, slow
  EXPECT_EQ(SpeedAllowance(0, 50), 200);     // as fast as possible, fast
  EXPECT_EQ(SpeedAllowance(-1, 0), kStepAllowanceFactor);  // nothing measured yet
  EXPECT_EQ(SpeedAllowance(1e9, 1e9), kStepAllowanceFactor);
  EXPECT_EQ(StepAllowance(0.001, 500000, 2), 3000);
}

// A SIM_MODEL of another simulation from another sender while the followed
// sim runs (a forged or stray one) is not logged and closes nothing (the
// writer closes older simulations when a model is queued); its states wait.
// Once the followed sim goes silent, the other is followed with the states
// that waited, as a restarted sim's are.
TEST_F(ReceiverTest, AnotherSimulationsModelClosesNothingUntilTheSimGoesSilent) {
  Start(1, 10.0, 0.3);
  model_t real = TwoBodyModel(5);
  real.sender = "simpartner-sim@testhost:100";
  model_t other = TwoBodyModel(6);
  other.sender = "simpartner-sim@elsewhere:200";
  Publish(channels::kModel, real);
  Publish(channels::kState, State(5, 1));
  Publish(channels::kModel, other);
  Publish(channels::kState, State(6, 1));
  Publish(channels::kState, State(5, 2));
  receiver_->Tick();
  std::vector<int64_t> models;
  int states_of_5 = 0;
  for (const Record& r : Queued()) {
    if (r.kind == RecordKind::kModel) models.push_back(r.simulation_id);
    if (r.kind == RecordKind::kState && r.simulation_id == 5) ++states_of_5;
    EXPECT_NE(r.simulation_id, 6) << "a record of the other simulation was queued";
  }
  EXPECT_EQ(models, std::vector<int64_t>{5});
  EXPECT_EQ(states_of_5, 2);
  EXPECT_EQ(receiver_->Stats().other_simulations, 1u);
  EXPECT_NE(out_.str().find("another simulation on the bus: id 6 from "
                            "'simpartner-sim@elsewhere:200'"),
            std::string::npos)
      << out_.str();
  // The followed sim falls silent; the other goes on.
  for (int i = 0; i < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    Publish(channels::kState, State(6, 2 + i));
    receiver_->Tick();
  }
  std::vector<int64_t> steps_of_6;
  for (const Record& r : Queued()) {
    if (r.kind == RecordKind::kModel) {
      EXPECT_EQ(r.simulation_id, 6);
    }
    if (r.kind == RecordKind::kState && r.simulation_id == 6) steps_of_6.push_back(StepOf(r));
  }
  EXPECT_EQ(steps_of_6, (std::vector<int64_t>{1, 2, 3, 4, 5, 6}));
}

// A new simulation id from the followed sim's own sender while it still
// talks is a copy (the sender is text anyone can write): another
// simulation. Once the followed one's status says it was reset, the new
// model is its successor, followed at once.
TEST_F(ReceiverTest, AResetIsFollowedOnceItsStatusSaysSoACopyIsNot) {
  Start();
  model_t before = TwoBodyModel(5), after = TwoBodyModel(6);
  before.sender = after.sender = "simpartner-sim@testhost:100";
  Publish(channels::kModel, before);
  Publish(channels::kState, State(5, 1));
  Publish(channels::kModel, after);  // a copy, another id
  std::vector<int64_t> models;
  for (const Record& r : Queued())
    if (r.kind == RecordKind::kModel) models.push_back(r.simulation_id);
  EXPECT_EQ(models, (std::vector<int64_t>{5}));
  EXPECT_EQ(receiver_->Stats().other_simulations, 1u);
  status_t reset{};
  reset.simulation_id = 5;
  reset.run_state = status_t::RUN_RESET;
  reset.step = 1;
  Publish(channels::kStatus, reset);
  Publish(channels::kModel, after);
  Publish(channels::kState, State(6, 1));
  models.clear();
  for (const Record& r : Queued())
    if (r.kind == RecordKind::kModel) models.push_back(r.simulation_id);
  EXPECT_EQ(models, (std::vector<int64_t>{6}));
}

// With a key (bus_signing.h), signed messages are logged as the message
// alone (the signature is not in the record); an unsigned model and state
// are refused, counted and never queued.
TEST_F(ReceiverTest, WithAKeyOnlySignedMessagesAreLogged) {
  BusSigning signing(BusSigning::Key{}), sim_key(BusSigning::Key{});
  Start(1, 10.0, 2.5, &signing);
  const model_t unsigned_model = TwoBodyModel(9);
  lcm_.publish(channels::kModel, &unsigned_model);  // no signature
  PublishSigned(&lcm_, channels::kModel, TwoBodyModel(5), &sim_key);
  PublishSigned(&lcm_, channels::kState, State(5, 1), &sim_key);
  const state_t unsigned_state = State(5, 2);
  lcm_.publish(channels::kState, &unsigned_state);  // no signature
  Drain();
  std::vector<Record> records = Queued();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].kind, RecordKind::kModel);
  EXPECT_EQ(records[0].simulation_id, 5);
  EXPECT_EQ(StepOf(records[1]), 1);
  state_t decoded;
  EXPECT_FALSE(simpartner::DecodeLcm(records[1].payload.data(), records[1].payload.size(), &decoded));
  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.channels.at(channels::kModel).unsigned_or_forged, 1u);
  EXPECT_EQ(stats.channels.at(channels::kState).unsigned_or_forged, 1u);
  // One line a second for every refusal of the process (bus_decode.h):
  // the model's is named, the state's within the second only counted.
  EXPECT_NE(out_.str().find("SIM_MODEL: "), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("bytes refused: no signature"), std::string::npos) << out_.str();
  EXPECT_EQ(out_.str().find("SIM_STATE: "), std::string::npos) << out_.str();
}

TEST(StepAllowanceTest, ThousandTimesRealTimePlusOneSecond) {
  // 1 ms steps: 1000 x real time is a million steps per second of wall
  // time, plus a second's worth.
  EXPECT_EQ(StepAllowance(0.001, 0), 1000000);
  EXPECT_EQ(StepAllowance(0.001, 500000), 1500000);
  EXPECT_EQ(StepAllowance(0.02, 2000000), 150000);
  EXPECT_EQ(StepAllowance(0.001, -5), 1000000);  // a clock step back counts as none
}

// A simulation whose sim falls silent (no SIM_STATE, no SIM_STATUS, no
// RUN_STOPPED) is closed with the last step seen and the reason; one that
// keeps sending SIM_STATUS (paused) is not.
TEST_F(ReceiverTest, ASilentSimIsClosedAtTheLastStepSeen) {
  Start(1, 0.3);
  Publish(channels::kModel, TwoBodyModel(5));
  Publish(channels::kModel, TwoBodyModel(6));
  for (int step = 1; step <= 7; ++step) Publish(channels::kState, State(5, step));
  status_t paused{};
  paused.simulation_id = 6;
  paused.run_state = status_t::RUN_PAUSED;
  for (int i = 0; i < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    Publish(channels::kStatus, paused);
    receiver_->Tick();
  }
  std::vector<Record> ended;
  for (Record& r : Queued())
    if (r.kind == RecordKind::kSimulationEnded) ended.push_back(std::move(r));
  ASSERT_EQ(ended.size(), 1u);
  EXPECT_EQ(ended[0].simulation_id, 5);
  const EndedPayload payload = ReadEnded(ended[0]);
  EXPECT_EQ(payload.last_step, 7);
  EXPECT_EQ(payload.kind, EndKind::kSilent);
  EXPECT_NE(payload.reason.find("the sim went silent: no SIM_STATE or SIM_STATUS for 0.3 s"),
            std::string::npos) << payload.reason;
  EXPECT_EQ(receiver_->Stats().simulations_silent, 1u);
  receiver_->Tick();  // once is enough
  EXPECT_TRUE(Queued().empty());
}

// A sim closed as silent that is heard again (stopped, not dead) is
// reopened, the silence goes in as a gap from the last step before it to
// the first after (none missing: the sim went on where it stopped), and
// its RUN_STOPPED then closes it.
TEST_F(ReceiverTest, ASilentSimHeardAgainIsReopenedWithTheSilenceAsAGap) {
  Start(1, 0.3);
  Publish(channels::kModel, TwoBodyModel(5));
  for (int step = 1; step <= 7; ++step) Publish(channels::kState, State(5, step));
  for (int i = 0; i < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    receiver_->Tick();
  }
  EXPECT_EQ(receiver_->Stats().simulations_silent, 1u);
  Queued();
  status_t running{};
  running.simulation_id = 5;
  running.run_state = status_t::RUN_RUNNING;
  running.step = 7;
  Publish(channels::kStatus, running);  // heard again: reopened at once
  Publish(channels::kState, State(5, 8));
  Publish(channels::kState, State(5, 9));
  status_t stopped = running;
  stopped.run_state = status_t::RUN_STOPPED;
  stopped.step = 9;
  Publish(channels::kStatus, stopped);
  const std::vector<Record> q = Queued();
  ASSERT_EQ(q.size(), 5u);
  EXPECT_EQ(q[0].kind, RecordKind::kSimulationReopened);
  EXPECT_EQ(q[0].simulation_id, 5);
  EXPECT_NE(ReadReopened(q[0]).find("last step seen 7"), std::string::npos) << ReadReopened(q[0]);
  ASSERT_EQ(q[1].kind, RecordKind::kGap);
  const GapPayload gap = ReadGap(q[1]);
  EXPECT_EQ(gap.first_step, 7);
  EXPECT_EQ(gap.last_step, 8);
  EXPECT_EQ(gap.missing, 0);
  EXPECT_NE(gap.reason.find("the sim was silent for 0."), std::string::npos) << gap.reason;
  EXPECT_EQ(q[2].kind, RecordKind::kState);
  EXPECT_EQ(q[3].kind, RecordKind::kState);
  ASSERT_EQ(q[4].kind, RecordKind::kSimulationEnded);
  EXPECT_EQ(ReadEnded(q[4]).kind, EndKind::kStopped);
  EXPECT_EQ(ReadEnded(q[4]).last_step, 9);
  const ReceiverStats stats = receiver_->Stats();
  EXPECT_EQ(stats.simulations_silent, 0u);
  EXPECT_EQ(stats.simulations_reopened, 1u);
  EXPECT_NE(out_.str().find("reopening it"), std::string::npos) << out_.str();
}

// Steps lost while the link was down are counted in the silence's gap
// (every 2nd step logged: 12, 14 and 16 lost between 11 and 17).
TEST_F(ReceiverTest, StepsLostDuringASilenceAreItsMissingSteps) {
  Start(2, 0.3);
  Publish(channels::kModel, TwoBodyModel(5));
  for (int step = 1; step <= 11; ++step) Publish(channels::kState, State(5, step));
  for (int i = 0; i < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    receiver_->Tick();
  }
  Queued();
  Publish(channels::kState, State(5, 17));
  const std::vector<Record> q = Queued();
  ASSERT_EQ(q.size(), 2u);  // reopened, gap; 17 is not a logged step
  ASSERT_EQ(q[1].kind, RecordKind::kGap);
  const GapPayload gap = ReadGap(q[1]);
  EXPECT_EQ(gap.first_step, 11);
  EXPECT_EQ(gap.last_step, 17);
  EXPECT_EQ(gap.missing, 3);
}

}  // namespace
}  // namespace simpartner::logger
