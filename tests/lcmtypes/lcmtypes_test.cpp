// Every message type survives encode/decode bit for bit, a damaged buffer
// is refused, and the jar that lets lcm-spy decode the bus has every type.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/model_request_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "../support/encode.h"

namespace simpartner {
namespace {

using test_support::Encode;

// Decodes, re-encodes and compares bytes; also checks that every truncation
// of the buffer is refused rather than read past its end.
template <class T>
T RoundTrip(const T& msg) {
  const std::vector<uint8_t> bytes = Encode(msg);
  T decoded;
  EXPECT_EQ(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  EXPECT_EQ(Encode(decoded), bytes);
  for (size_t cut : {size_t{0}, size_t{7}, bytes.size() / 2, bytes.size() - 1}) {
    if (cut >= bytes.size()) continue;
    T partial;
    EXPECT_LT(partial.decode(bytes.data(), 0, static_cast<int>(cut)), 0) << "cut at " << cut;
  }
  // A different type's fingerprint is refused.
  std::vector<uint8_t> wrong = bytes;
  wrong[0] ^= 0x5a;
  T mismatched;
  EXPECT_LT(mismatched.decode(wrong.data(), 0, static_cast<int>(wrong.size())), 0);
  return decoded;
}

model_t SampleModel() {
  model_t m{};
  m.utime = 1234567;
  m.simulation_id = 42;
  m.host = "host-a";
  m.engine = "mujoco";
  m.world_file = "models/worlds/flat_ground.xml";
  m.world_name = "Flat";
  m.parameters = "stepsize=0.001\n";
  m.step_size = 0.001;
  m.state_every = 1;
  m.gravity[1] = -9.81;
  m.up[1] = 1.0;
  m.has_plane = true;
  m.plane[1] = 1.0;
  m.heightfield.present = true;
  m.heightfield.rows = 2;
  m.heightfield.columns = 3;
  m.heightfield.num_samples = 6;
  m.heightfield.samples = {0.f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f};
  m.num_materials = 1;
  m.materials.resize(1);
  m.materials[0].name = "ice";
  m.materials[0].mu = 0.025;
  m.num_robots = 1;
  m.robots.resize(1);
  m.robots[0].name = "WorkPartner";
  m.robots[0].total_mass = 202.0;
  m.num_bodies = 2;
  m.bodies.resize(2);
  m.bodies[0].name = "Wheel1";
  m.bodies[0].geometry.kind = geometry_t::KIND_CYLINDER;
  m.bodies[0].geometry.size[0] = 0.235;
  m.bodies[0].mass = 5.0;
  m.bodies[0].initial_orientation[0] = 1.0;
  m.bodies[1].name = "Calf1";
  m.bodies[1].id = 1;
  m.num_joints = 1;
  m.joints.resize(1);
  m.joints[0].name = "Axle1";
  m.joints[0].kind = joint_t::KIND_HINGE;
  m.joints[0].body1 = 1;
  m.joints[0].axis[0][2] = 1.0;
  m.joints[0].lo_stop[0] = -INFINITY;
  m.joints[0].hi_stop[0] = INFINITY;
  m.num_sensors = 1;
  m.sensors.resize(1);
  m.sensors[0].name = "Scanner";
  m.sensors[0].kind = sensor_t::KIND_SCANNER;
  m.sensors[0].num_params = 3;
  m.sensors[0].params = {11, 0.1, 10};
  m.num_actuators = 1;
  m.actuators.resize(1);
  m.actuators[0].name = "Axle1Motor";
  m.actuators[0].port = 1028;
  return m;
}

TEST(LcmTypes, ModelRoundTrips) {
  const model_t decoded = RoundTrip(SampleModel());
  EXPECT_EQ(decoded.bodies.at(0).name, "Wheel1");
  EXPECT_EQ(decoded.heightfield.samples.at(5), 0.5f);
  EXPECT_TRUE(std::isinf(decoded.joints.at(0).lo_stop[0]));
  EXPECT_EQ(decoded.sensors.at(0).params.at(0), 11.0);
  EXPECT_EQ(decoded.engine, "mujoco");
}

TEST(LcmTypes, StateRoundTrips) {
  state_t s{};
  s.simulation_id = 42;
  s.step = 1000;
  s.sim_time = 1.0;
  s.num_bodies = 25;
  s.bodies.resize(25);
  for (int i = 0; i < 25; ++i) {
    s.bodies[i].position[1] = 0.235 + i;
    s.bodies[i].orientation[0] = 1.0;
    s.bodies[i].contact_force[1] = 600.0 - i;
  }
  s.num_joints = 24;
  s.joints.resize(24);
  s.joints[3].position[0] = 0.2972;
  s.joints[3].continuous_position[0] = 0.2972 + 6 * 3.14159265358979323846;  // three turns on
  const state_t decoded = RoundTrip(s);
  EXPECT_EQ(decoded.bodies.at(24).position[1], 24.235);
  EXPECT_EQ(decoded.joints.at(3).position[0], 0.2972);
  EXPECT_EQ(decoded.joints.at(3).continuous_position[0], 0.2972 + 6 * 3.14159265358979323846);
}

TEST(LcmTypes, CommandAndReplyRoundTrip) {
  command_t c{};
  c.request_id = 7;
  c.sender = "sequencer@h:1";
  c.port = 1028;
  c.action = command_t::ACTION_SET;
  c.apply_at_step = 500;
  c.num_values = 6;
  c.values = {1000, 1000, 100, 0, 0, 0.2};
  c.text = "1000,1000,100,0,0,0.2";
  c.simulation_id = 1700000000123456;
  EXPECT_EQ(RoundTrip(c).values.at(5), 0.2);
  EXPECT_EQ(RoundTrip(c).simulation_id, 1700000000123456);

  command_reply_t r{};
  r.request_id = 7;
  r.accepted = false;
  r.reason = "values[2]: NaN is not a finite number";
  r.num_previous = 2;
  r.previous = {1.0, 2.0};
  EXPECT_EQ(RoundTrip(r).reason, r.reason);
}

TEST(LcmTypes, SensorControlStatusRequestRoundTrip) {
  sensor_reading_t s{};
  s.kind = sensor_t::KIND_SCANNER;
  s.num_values = 11;
  s.values.assign(11, 5.335);
  EXPECT_EQ(RoundTrip(s).values.size(), 11u);

  control_t c{};
  c.action = control_t::ACTION_STEP;
  c.steps = 10;
  c.simulation_id = -3;
  EXPECT_EQ(RoundTrip(c).steps, 10);
  EXPECT_EQ(RoundTrip(c).simulation_id, -3);

  status_t st{};
  st.engine = "ode";
  st.run_state = status_t::RUN_FAULTED;
  st.num_warnings = 1;
  st.warnings.resize(1);
  st.warnings[0].message = "non-finite state";
  st.warnings[0].num_bodies = 2;
  st.warnings[0].bodies = {"Wheel1", "Calf1"};
  EXPECT_EQ(RoundTrip(st).warnings.at(0).bodies.at(1), "Calf1");
  EXPECT_EQ(RoundTrip(st).engine, "ode");

  model_request_t q{};
  q.sender = "viewer";
  EXPECT_EQ(RoundTrip(q).sender, "viewer");
}

// A count that disagrees with its array cannot be encoded into a message
// that decodes differently: the encoder uses the count field.
TEST(LcmTypes, CountFieldGovernsEncoding) {
  sensor_reading_t s{};
  s.num_values = 2;
  s.values = {1.0, 2.0, 3.0};
  const sensor_reading_t decoded = RoundTrip(s);
  EXPECT_EQ(decoded.values.size(), 2u);
}

TEST(LcmTypes, JarHasAClassPerType) {
  const std::string jar = SP_LCM_JAR;
  FILE* pipe = ::popen(("jar tf '" + jar + "' 2>&1").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::set<std::string> entries;
  char line[512];
  while (std::fgets(line, sizeof line, pipe)) {
    std::string entry(line);
    while (!entry.empty() && (entry.back() == '\n' || entry.back() == '\r')) entry.pop_back();
    entries.insert(entry);
  }
  ASSERT_EQ(::pclose(pipe), 0) << "jar tf failed for " << jar;
  std::istringstream types(SP_LCM_TYPES);
  std::string type;
  int count = 0;
  while (std::getline(types, type, ',')) {
    ++count;
    EXPECT_TRUE(entries.count("simpartner/" + type + ".class")) << type << " missing from " << jar;
  }
  EXPECT_GE(count, 19);
}

// lcm-spy keeps working on a signed bus: lcm-java decodes a message that
// carries a signature trailer (bus_signing.h) and ignores the trailer.
TEST(LcmTypes, LcmJavaDecodesASignedMessage) {
  const std::string command = "java -cp '" + std::string(SP_LCM_JAR_SYSTEM) + ":" + SP_LCM_JAR +
                              "' '" + SP_SOURCE_DIR + "/tests/lcmtypes/SignedDecode.java' 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char line[512];
  while (std::fgets(line, sizeof line, pipe)) out += line;
  EXPECT_EQ(::pclose(pipe), 0) << out;
  EXPECT_EQ(out, "sender=x@y:1 action=3 steps=7\n");
}

}  // namespace
}  // namespace simpartner
