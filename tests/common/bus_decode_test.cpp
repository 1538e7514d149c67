// The total decoder: every hostile datagram is refused with a reason that
// names the field, well-formed messages decode as lcm-gen's decoder would,
// and whatever the layout check lets through, lcm-gen's decoder reads
// without throwing.
#include "simpartner/bus_decode.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "../support/encode.h"
#include "../support/hostile_corpus.h"
#include "simpartner/bus_url.h"
#include "simpartner/channels.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/image_t.hpp"
#include "simpartner/model_request_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/state_request_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/sync_reply_t.hpp"
#include "simpartner/sync_t.hpp"

namespace simpartner {
namespace {

using Bytes = std::vector<uint8_t>;
using test_support::Encode;

// The decode each channel's subscribers do, by channel name.
std::optional<DecodeFailure> DecodeForChannel(const std::string& channel, const Bytes& bytes) {
  static const std::map<std::string, std::function<std::optional<DecodeFailure>(const Bytes&)>>
      decoders = {
          {channels::kCommand, [](const Bytes& b) { command_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kCommandReply, [](const Bytes& b) { command_reply_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kControl, [](const Bytes& b) { control_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kModel, [](const Bytes& b) { model_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kModelRequest, [](const Bytes& b) { model_request_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kSensor, [](const Bytes& b) { sensor_reading_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kState, [](const Bytes& b) { state_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kStatus, [](const Bytes& b) { status_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kStateRequest, [](const Bytes& b) { state_request_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kSync, [](const Bytes& b) { sync_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kSyncReply, [](const Bytes& b) { sync_reply_t m; return DecodeLcm(b.data(), b.size(), &m); }},
          {channels::kImage, [](const Bytes& b) { image_t m; return DecodeLcm(b.data(), b.size(), &m); }},
      };
  return decoders.at(channel)(bytes);
}

TEST(HostileCorpus, CoversEveryChannelWithAtLeastThirtyMessages) {
  const auto corpus = test_support::HostileCorpus(1);
  EXPECT_GE(corpus.size(), 30u);
  std::map<std::string, int> per_channel;
  for (const auto& m : corpus) ++per_channel[m.channel];
  for (const char* channel : {channels::kCommand, channels::kCommandReply, channels::kControl,
                              channels::kModel, channels::kModelRequest, channels::kSensor,
                              channels::kState, channels::kStatus, channels::kStateRequest,
                              channels::kSync, channels::kSyncReply, channels::kImage})
    EXPECT_GE(per_channel[channel], 2) << channel;
}

TEST(BusDecode, RefusesEveryMalformedMessageOfTheCorpusAndDecodesTheRest) {
  for (const auto& m : test_support::HostileCorpus(1)) {
    SCOPED_TRACE(m.name);
    const auto failure = DecodeForChannel(m.channel, m.bytes);
    EXPECT_EQ(failure.has_value(), m.undecodable) << (failure ? failure->reason : "decoded");
    // The layout check is what refuses; lcm-gen's decoder never sees it.
    if (failure) {
      EXPECT_EQ(failure->reason.find("decoder threw"), std::string::npos);
    }
  }
}

TEST(BusDecode, ReasonsNameTheFieldAndTheValue) {
  std::map<std::string, std::string> reason;
  for (const auto& m : test_support::HostileCorpus(1)) {
    const auto failure = DecodeForChannel(m.channel, m.bytes);
    reason[m.name] = failure ? failure->reason : "";
  }
  EXPECT_EQ(reason["command_t sender length 0"],
            "field 'sender' at byte 32: string length 0 (an LCM string holds at least its NUL)");
  EXPECT_EQ(reason["command_t sender length -5"],
            "field 'sender' at byte 32: string length -5 (an LCM string holds at least its NUL)");
  EXPECT_NE(reason["command_t num_values -1"].find("field 'num_values'"), std::string::npos);
  EXPECT_NE(reason["command_t num_values -1"].find("count -1 is negative"), std::string::npos);
  EXPECT_NE(reason["command_t num_values 1e8"].find("100000000"), std::string::npos);
  EXPECT_NE(reason["command_t num_values 65 (bound 64)"].find("beyond the bound of 64"),
            std::string::npos);
  EXPECT_NE(reason["state_t num_bodies 2^31-1"].find("2147483647 is beyond the bound of 100000"),
            std::string::npos);
  // The hand-built heads of model_t and status_t reach the field they name.
  EXPECT_NE(reason["model_t heightfield num_samples 2^31-1"].find("field 'heightfield.samples' at byte 260: 2147483647 elements"),
            std::string::npos) << reason["model_t heightfield num_samples 2^31-1"];
  EXPECT_NE(reason["model_t num_materials -1"].find("field 'num_materials'"), std::string::npos)
      << reason["model_t num_materials -1"];
  EXPECT_NE(reason["status_t num_warnings -1"].find("field 'num_warnings'"), std::string::npos)
      << reason["status_t num_warnings -1"];
  EXPECT_NE(reason["status_t warning body name length -5"].find("field 'warnings[0].bodies[0]'"),
            std::string::npos);
  EXPECT_NE(reason["command_t with 3 bytes after it"].find("3 bytes follow the message"),
            std::string::npos);
  EXPECT_NE(reason["state_t sent on SIM_COMMAND"].find("another type or version"),
            std::string::npos);
  EXPECT_EQ(reason["model_request_t sender with a NUL inside"],
            "field 'sender' at byte 16: string of length 4 has a NUL at character 1");
  EXPECT_EQ(reason["model_request_t sender without its NUL"],
            "field 'sender' at byte 16: string of length 3 does not end with a NUL");
  EXPECT_NE(reason["empty datagram on SIM_MODEL_REQUEST"].find("too short for a fingerprint"),
            std::string::npos);
}

model_t FullModel() {
  model_t m{};
  m.simulation_id = 42;
  m.host = "h";
  m.engine = "mujoco";
  m.heightfield.present = true;
  m.heightfield.num_samples = 4;
  m.heightfield.samples = {0.f, 1.f, 2.f, 3.f};
  m.num_materials = 1;
  m.materials.resize(1);
  m.materials[0].name = "ice";
  m.num_robots = 1;
  m.robots.resize(1);
  m.robots[0].name = "WorkPartner";
  m.num_bodies = 2;
  m.bodies.resize(2);
  m.bodies[0].name = "Wheel1";
  m.bodies[1].name = "Calf1";
  m.num_joints = 1;
  m.joints.resize(1);
  m.joints[0].name = "Turner";
  m.num_sensors = 1;
  m.sensors.resize(1);
  m.sensors[0].name = "Scanner";
  m.sensors[0].num_params = 3;
  m.sensors[0].params = {11, 0.1, 10};
  m.num_actuators = 1;
  m.actuators.resize(1);
  m.actuators[0].name = "TurnerMotor";
  return m;
}

status_t FullStatus() {
  status_t s{};
  s.host = "h";
  s.engine = "mujoco";
  s.num_warnings = 2;
  s.warnings.resize(2);
  s.warnings[0].source = "ode";
  s.warnings[0].message = "LCP internal error";
  s.warnings[0].num_bodies = 2;
  s.warnings[0].bodies = {"Wheel1", "Calf1"};
  s.warnings[1].source = "health";
  return s;
}

TEST(BusDecode, WellFormedMessagesDecodeExactlyAsLcmGenDecodesThem) {
  const model_t model = FullModel();
  model_t decoded_model;
  ASSERT_FALSE(DecodeLcm(Encode(model).data(), Encode(model).size(), &decoded_model));
  EXPECT_EQ(Encode(decoded_model), Encode(model));
  EXPECT_EQ(decoded_model.sensors[0].params[2], 10);

  const status_t status = FullStatus();
  status_t decoded_status;
  ASSERT_FALSE(DecodeLcm(Encode(status).data(), Encode(status).size(), &decoded_status));
  EXPECT_EQ(decoded_status.warnings[0].bodies[1], "Calf1");
  EXPECT_EQ(decoded_status.engine, "mujoco");
  EXPECT_EQ(decoded_model.engine, "mujoco");

  state_t state{};
  state.num_bodies = 3;
  state.bodies.resize(3);
  state.bodies[2].position[1] = 1.5;
  state.num_joints = 2;
  state.joints.resize(2);
  state_t decoded_state;
  ASSERT_FALSE(DecodeLcm(Encode(state).data(), Encode(state).size(), &decoded_state));
  EXPECT_EQ(decoded_state.bodies[2].position[1], 1.5);
  EXPECT_EQ(decoded_state.joints.size(), 2u);
}

// Writes `value` as a big-endian int32 at `at`.
Bytes Patched(Bytes bytes, size_t at, uint32_t value) {
  for (int i = 0; i < 4 && at + static_cast<size_t>(i) < bytes.size(); ++i)
    bytes[at + static_cast<size_t>(i)] = static_cast<uint8_t>(value >> (8 * (3 - i)));
  return bytes;
}

// Soundness: wherever a length or count may sit, the extreme values are
// either refused by the layout check or read by lcm-gen's decoder without
// an exception and to the last byte. Completeness: what lcm-gen reads
// cleanly is accepted, unless a stated bound refuses it.
template <class T>
void SweepExtremeValues(const T& message) {
  const Bytes clean = Encode(message);
  for (size_t at = 8; at < clean.size(); ++at) {
    for (uint32_t value : {0u, 0xffffffffu, 0xfffffffbu, 0x7fffffffu, 0x80000000u, 0x00010000u}) {
      const Bytes bytes = Patched(clean, at, value);
      const auto layout = CheckLcmLayout(T::getTypeName(), T::getHash(), bytes.data(), bytes.size());
      if (!layout) {
        T decoded;
        int used = -2;
        EXPECT_NO_THROW(used = decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())))
            << T::getTypeName() << " value " << value << " at byte " << at;
        EXPECT_EQ(used, static_cast<int>(bytes.size()))
            << T::getTypeName() << " value " << value << " at byte " << at;
      }
      T out;
      EXPECT_NO_THROW(DecodeLcm(bytes.data(), bytes.size(), &out));
    }
  }
}

TEST(BusDecode, ExtremeValuesAtEveryOffsetAreRefusedOrReadSafely) {
  SweepExtremeValues(FullModel());
  SweepExtremeValues(FullStatus());
  command_t command{};
  command.sender = "me";
  command.target = "Turner";
  command.num_values = 3;
  command.values = {1, 2, 3};
  command.text = "1,2,3";
  SweepExtremeValues(command);
  sensor_reading_t reading{};
  reading.name = "Scanner";
  reading.num_values = 2;
  reading.values = {1, 2};
  SweepExtremeValues(reading);
}

TEST(BusDecode, EveryTruncationIsRefusedWithoutThrowing) {
  const Bytes full = Encode(FullModel());
  for (size_t cut = 0; cut < full.size(); ++cut) {
    model_t out;
    const auto failure = DecodeLcm(full.data(), cut, &out);
    ASSERT_TRUE(failure.has_value()) << "cut at " << cut;
    EXPECT_EQ(failure->reason.find("decoder threw"), std::string::npos) << failure->reason;
  }
}

TEST(BadMessageCounter, CountsPerChannelAndPrintsTheFirstThenOneInAThousand) {
  BadMessageCounter counter;
  int printed = 0;
  for (int i = 0; i < 2500; ++i) printed += counter.Count("SIM_COMMAND", "bad " + std::to_string(i));
  EXPECT_TRUE(counter.Count("SIM_STATE", "worse"));
  EXPECT_EQ(printed, 3);  // 1st, 1000th, 2000th
  EXPECT_EQ(counter.total(), 2501u);
  EXPECT_EQ(counter.count("SIM_COMMAND"), 2500u);
  EXPECT_EQ(counter.count("SIM_CONTROL"), 0u);
  EXPECT_EQ(counter.Summary(), "SIM_COMMAND 2500, SIM_STATE 1");
  EXPECT_EQ(counter.last_description(), "worse");
}

TEST(DecodeFromBus, DescribesTheChannelTypeSizeAndReason) {
  BadMessageCounter counter;
  const auto corpus = test_support::HostileCorpus(1);
  const auto& killer = corpus.front();
  ASSERT_EQ(killer.name, "command_t sender length 0");
  ASSERT_EQ(killer.bytes.size(), 48u);
  command_t command;
  bool print = false;
  const auto description =
      DecodeFromBus(killer.channel, killer.bytes.data(), killer.bytes.size(), &command, &counter, &print);
  ASSERT_TRUE(description.has_value());
  EXPECT_EQ(*description,
            "SIM_COMMAND: 48 bytes refused as simpartner.command_t: field 'sender' at byte 32: "
            "string length 0 (an LCM string holds at least its NUL)");
  EXPECT_TRUE(print);
  EXPECT_EQ(counter.count("SIM_COMMAND"), 1u);
}

// Every process that must not lose a datagram (logger, client, sequencer)
// opens its udpm socket with a 4 MiB buffer unless the URL sets one.
TEST(BusUrlTest, ReceiveBufferIsAddedToUdpmUrls) {
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667?ttl=0"),
            "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(WithReceiveBuffer("udpm://239.255.76.67:7667"),
            "udpm://239.255.76.67:7667?recv_buf_size=4194304");
  EXPECT_EQ(WithReceiveBuffer("udpm://x:1?recv_buf_size=100"), "udpm://x:1?recv_buf_size=100");
  EXPECT_EQ(WithReceiveBuffer("memq://"), "memq://");
}

}  // namespace
}  // namespace simpartner
