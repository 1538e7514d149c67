#include "hostile_corpus.h"

#include <cmath>
#include <cstring>
#include <limits>

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
#include "encode.h"

namespace simpartner::test_support {

RawMessage& RawMessage::F64(double v) {
  uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return Put(bits, 8);
}

RawMessage& RawMessage::F32(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return Put(bits, 4);
}

RawMessage& RawMessage::Str(const std::string& s) {
  I32(static_cast<int32_t>(s.size() + 1));
  bytes_.insert(bytes_.end(), s.begin(), s.end());
  bytes_.push_back(0);
  return *this;
}

RawMessage& RawMessage::StrLength(int32_t length) { return I32(length); }

namespace {

constexpr int32_t kHugeCount = std::numeric_limits<int32_t>::max();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// command_t up to (not including) num_values, with the given strings.
RawMessage CommandHead() {
  RawMessage m(command_t::getHash());
  m.I64(1).I64(77).I64(0).Str("hostile@nowhere:1").Str("").Str("Turner").I32(0).I8(0).I64(-1);
  return m;
}

RawMessage StateHead(int64_t simulation_id, int64_t step) {
  RawMessage m(state_t::getHash());
  m.I64(1).I64(simulation_id).I64(step).F64(static_cast<double>(step) * 0.001);
  return m;
}

RawMessage StatusHead(int64_t simulation_id) {
  RawMessage m(status_t::getHash());
  m.I64(1).I64(simulation_id).Str("elsewhere").Str("ode").I8(0).I64(5).F64(0.005).F64(1).F64(1).F64(1e-4);
  m.I64(0).I64(0).I64(0);
  return m;
}

RawMessage SensorHead(int64_t simulation_id) {
  RawMessage m(sensor_reading_t::getHash());
  m.I64(1).I64(simulation_id).I64(5).F64(0.005).I32(0).Str("Scanner").I8(2);
  return m;
}

RawMessage ReplyHead(int64_t simulation_id) {
  RawMessage m(command_reply_t::getHash());
  m.I64(1).I64(simulation_id).I64(77).Str("someone@else:2").Str("Turner").I8(1);
  return m;
}

// model_t through the heightfield's material, with `host` given raw.
RawMessage ModelHead(int64_t simulation_id, int32_t host_length) {
  RawMessage m(model_t::getHash());
  m.I64(1).I64(simulation_id);
  if (host_length == 1) m.Str("");
  else m.StrLength(host_length);
  // sender, engine, world_file, world_name, parameters
  m.Str("hostile@nowhere:1").Str("ode").Str("w.xml").Str("w").Str("").F64(0.001).I32(1);
  m.F64(0).F64(-9.81).F64(0).F64(0).F64(1).F64(0);
  m.I8(1).F64(0).F64(1).F64(0).F64(0).Str("");
  // heightfield: present, rows, columns, width, depth, scale, offset,
  // thickness, position[3], material
  m.I8(1).I32(2).I32(2).F64(1).F64(1).F64(1).F64(0).F64(1).F64(0).F64(0).F64(0).Str("");
  return m;
}

// image_t up to its size, with `name_length` given raw.
RawMessage ImageHead(int64_t simulation_id, int32_t name_length) {
  RawMessage m(image_t::getHash());
  m.I64(1).I64(simulation_id).I64(5).F64(0.005).I32(0);
  if (name_length == 1) m.Str("");
  else m.StrLength(name_length);
  return m;
}

}  // namespace

std::vector<HostileMessage> HostileCorpus(int64_t simulation_id) {
  using channels::kCommand;
  using channels::kCommandReply;
  using channels::kControl;
  using channels::kModel;
  using channels::kModelRequest;
  using channels::kSensor;
  using channels::kState;
  using channels::kStateRequest;
  using channels::kStatus;
  using channels::kSync;
  using channels::kSyncReply;
  std::vector<HostileMessage> corpus;
  auto bad = [&](std::string name, const char* channel, std::vector<uint8_t> bytes) {
    corpus.push_back({std::move(name), channel, std::move(bytes), true});
  };
  auto nonsense = [&](std::string name, const char* channel, std::vector<uint8_t> bytes) {
    corpus.push_back({std::move(name), channel, std::move(bytes), false});
  };

  // --- SIM_COMMAND: command_t
  {
    RawMessage m(command_t::getHash());
    m.I64(1).I64(1).I64(0).StrLength(0);  // the 48-byte killer of the issue
    m.Zeros(48 - m.bytes().size());
    bad("command_t sender length 0", kCommand, m.bytes());
  }
  {
    RawMessage m(command_t::getHash());
    m.I64(1).I64(1).I64(0).StrLength(-5).Zeros(28);
    bad("command_t sender length -5", kCommand, m.bytes());
  }
  {
    RawMessage m(command_t::getHash());
    m.I64(1).I64(1).I64(0).Str("x").Str("").StrLength(kHugeCount).Zeros(16);
    bad("command_t target length 2^31-1", kCommand, m.bytes());
  }
  bad("command_t num_values -1", kCommand, CommandHead().I32(-1).Str("").bytes());
  bad("command_t num_values 2^31-1", kCommand, CommandHead().I32(kHugeCount).Str("").bytes());
  bad("command_t num_values 1e8", kCommand, CommandHead().I32(100000000).Str("").bytes());
  {
    RawMessage m = CommandHead();
    m.I32(65);
    for (int i = 0; i < 65; ++i) m.F64(0);
    bad("command_t num_values 65 (bound 64)", kCommand, m.Str("").bytes());
  }
  bad("command_t truncated in its values", kCommand, CommandHead().I32(6).F64(1000).F64(1000).bytes());
  bad("command_t with 3 bytes after it", kCommand,
      CommandHead().I32(0).Str("").I8(1).I8(2).I8(3).bytes());
  {
    state_t s{};
    s.simulation_id = simulation_id;
    bad("state_t sent on SIM_COMMAND", kCommand, Encode(s));
  }
  {
    command_t c{};
    c.sender = "hostile@nowhere:1";
    c.target = "Turner";
    c.action = command_t::ACTION_SET;
    c.apply_at_step = -1;
    c.values = {1000, kNaN, 1e308, 0, 0, 0.1};
    c.num_values = 6;
    nonsense("command_t NaN and 1e308 values", kCommand, Encode(c));
    c.values = {1000, 1000, 100, 0, 0, 0.1};
    c.action = 99;
    nonsense("command_t action 99", kCommand, Encode(c));
    c.action = command_t::ACTION_SET;
    c.target = "";
    c.port = -1;
    nonsense("command_t port -1", kCommand, Encode(c));
    c.port = 0;
    c.target = std::string(5000, 'A');
    nonsense("command_t 5000-character target", kCommand, Encode(c));
    c.target = "Turner";
    c.apply_at_step = std::numeric_limits<int64_t>::max() / 2;
    nonsense("command_t apply_at_step 2^62", kCommand, Encode(c));
    c.apply_at_step = -1;
    c.simulation_id = simulation_id + 1;
    nonsense("command_t for another simulation", kCommand, Encode(c));
  }

  // --- SIM_CONTROL: control_t
  {
    RawMessage m(control_t::getHash());
    m.I64(1).I64(1).I64(0).StrLength(0).I8(0).I64(0).F64(0);
    bad("control_t sender length 0", kControl, m.bytes());
  }
  bad("control_t of 3 bytes", kControl, {1, 2, 3});
  {
    control_t c{};
    c.sender = "hostile@nowhere:1";
    c.action = 99;
    nonsense("control_t action 99", kControl, Encode(c));
    c.action = control_t::ACTION_STEP;
    c.steps = -1;
    nonsense("control_t step -1", kControl, Encode(c));
    c.steps = std::numeric_limits<int64_t>::max();
    nonsense("control_t step 2^63-1", kControl, Encode(c));
    c.action = control_t::ACTION_SET_SPEED;
    c.speed = kNaN;
    nonsense("control_t speed NaN", kControl, Encode(c));
    c.speed = 1e-300;
    nonsense("control_t speed 1e-300", kControl, Encode(c));
    c.action = control_t::ACTION_QUIT;
    c.simulation_id = simulation_id + 1;
    nonsense("control_t quit for another simulation", kControl, Encode(c));
  }

  // --- SIM_MODEL_REQUEST: model_request_t
  {
    RawMessage m(model_request_t::getHash());
    m.I64(1).StrLength(-1);
    bad("model_request_t sender length -1", kModelRequest, m.bytes());
  }
  bad("empty datagram on SIM_MODEL_REQUEST", kModelRequest, {});
  {
    RawMessage m(model_request_t::getHash());
    m.I64(1).I32(4).I8('a').I8(0).I8('b').I8(0);
    bad("model_request_t sender with a NUL inside", kModelRequest, m.bytes());
    RawMessage n(model_request_t::getHash());
    n.I64(1).I32(3).I8('a').I8('b').I8('c');
    bad("model_request_t sender without its NUL", kModelRequest, n.bytes());
  }

  // --- SIM_STATE_REQUEST: state_request_t
  {
    RawMessage m(state_request_t::getHash());
    m.I64(1).I64(simulation_id).StrLength(-1);
    bad("state_request_t sender length -1", kStateRequest, m.bytes());
    state_request_t r{};
    r.simulation_id = simulation_id + 1;
    r.sender = "elsewhere";
    nonsense("state_request_t for another simulation", kStateRequest, Encode(r));
  }

  // --- SIM_SYNC: sync_t (lock-step marks)
  {
    auto head = [&](int32_t num_commands) {
      RawMessage m(sync_t::getHash());
      m.I64(1).I64(simulation_id).Str("ctl").Str("ctl@host:1").Str("").I8(sync_t::ACTION_DONE);
      m.I64(1).I64(5).I32(num_commands);
      return m;
    };
    bad("sync_t num_commands -1", kSync, head(-1).bytes());
    bad("sync_t num_commands 257 (bound 256)", kSync, head(257).bytes());
    RawMessage m(sync_t::getHash());
    m.I64(1).I64(simulation_id).StrLength(0);
    bad("sync_t controller length 0", kSync, m.bytes());
    sync_t s{};
    s.simulation_id = simulation_id;
    s.controller = "forger";
    s.sender = "forger@elsewhere:1";
    s.action = sync_t::ACTION_DONE;
    s.tick = 1000000000000;
    nonsense("sync_t DONE for a tick that never happened, never joined", kSync, Encode(s));
    s.action = sync_t::ACTION_JOIN;
    s.period = 0;
    nonsense("sync_t JOIN with period 0", kSync, Encode(s));
    s.action = sync_t::ACTION_LEAVE;
    nonsense("sync_t LEAVE of a controller that never joined", kSync, Encode(s));
    s.action = 42;
    nonsense("sync_t unknown action 42", kSync, Encode(s));
    s.action = sync_t::ACTION_JOIN;
    s.period = 1;
    s.simulation_id = simulation_id + 1;
    nonsense("sync_t JOIN for another simulation", kSync, Encode(s));
  }

  // --- SIM_SYNC_REPLY: sync_reply_t
  {
    RawMessage m(sync_reply_t::getHash());
    m.I64(1).I64(simulation_id).Str("ctl").Str("ctl@host:1").I8(sync_reply_t::EVENT_RELEASED);
    m.I64(1).I64(5).StrLength(-1);
    bad("sync_reply_t reason length -1", kSyncReply, m.bytes());
    bad("empty datagram on SIM_SYNC_REPLY", kSyncReply, {});
  }

  // --- SIM_IMAGE: image_t
  bad("image_t name length 0", channels::kImage, ImageHead(simulation_id, 0).bytes());
  bad("image_t num_bytes -1", channels::kImage,
      ImageHead(simulation_id, 1).Str("R").I32(2).I32(2).I8(0).I32(-1).bytes());
  bad("image_t num_bytes 2^31-1", channels::kImage,
      ImageHead(simulation_id, 1).Str("R").I32(2).I32(2).I8(0).I32(kHugeCount).bytes());
  bad("image_t num_bytes 67108865 (bound 67108864)", channels::kImage,
      ImageHead(simulation_id, 1).Str("R").I32(4096).I32(4096).I8(0).I32(67108865).bytes());
  bad("empty datagram on SIM_IMAGE", channels::kImage, {});
  {
    image_t image{};
    image.simulation_id = simulation_id;
    image.name = "HeadCamera";
    image.robot = "WorkPartner";
    image.width = 640;
    image.height = 480;
    image.data.assign(12, 0);  // not 640 x 480 x 3
    image.num_bytes = 12;
    nonsense("image_t 640x480 RGB8 with 12 bytes", channels::kImage, Encode(image));
  }

  // --- SIM_STATE: state_t
  bad("state_t num_bodies -1", kState, StateHead(simulation_id, 5).I32(-1).I32(0).bytes());
  bad("state_t num_bodies 2^31-1", kState, StateHead(simulation_id, 5).I32(kHugeCount).I32(0).bytes());
  bad("state_t num_bodies 100001 (bound 100000)", kState,
      StateHead(simulation_id, 5).I32(100001).I32(0).bytes());
  bad("state_t num_joints -7", kState, StateHead(simulation_id, 5).I32(0).I32(-7).bytes());
  {
    state_t s{};
    s.simulation_id = simulation_id;
    s.step = 3;
    s.num_bodies = 1;  // the model has more
    s.bodies.resize(1);
    s.bodies[0].orientation[0] = 1;
    nonsense("state_t with 1 body, not the model's count", kState, Encode(s));
    s.step = 500000000;
    s.num_bodies = 0;
    s.bodies.clear();
    nonsense("state_t step 5e8, no bodies", kState, Encode(s));
    s.simulation_id = simulation_id + 12345;
    s.step = 4;
    nonsense("state_t of an unknown simulation", kState, Encode(s));
  }

  // --- SIM_STATUS: status_t
  {
    RawMessage m(status_t::getHash());
    m.I64(1).I64(simulation_id).StrLength(0).Zeros(60);
    bad("status_t host length 0", kStatus, m.bytes());
  }
  bad("status_t num_warnings -1", kStatus, StatusHead(simulation_id).I16(-1).bytes());
  {
    RawMessage m = StatusHead(simulation_id);
    m.I16(1).I64(5).I8(1).Str("bus").Str("x").I16(32767);
    bad("status_t warning with 32767 bodies claimed", kStatus, m.bytes());
  }
  {
    RawMessage m = StatusHead(simulation_id);
    m.I16(1).I64(5).I8(1).Str("bus").Str("x").I16(1).StrLength(-5).Zeros(8);
    bad("status_t warning body name length -5", kStatus, m.bytes());
  }

  // --- SIM_MODEL: model_t
  bad("model_t host length 0", kModel, ModelHead(simulation_id, 0).Zeros(64).bytes());
  bad("model_t heightfield num_samples 2^31-1", kModel,
      ModelHead(simulation_id, 1).I32(kHugeCount).F32(0).bytes());
  bad("model_t num_materials -1", kModel,
      ModelHead(simulation_id, 1).I32(0).I16(-1).I16(0).I32(0).I32(0).I32(0).I32(0).bytes());
  {
    model_t m{};
    m.simulation_id = simulation_id + 999;
    m.step_size = 0.001;
    m.state_every = 1;
    m.num_bodies = 1;
    m.bodies.resize(1);
    m.bodies[0].name = "Ghost";
    m.bodies[0].robot = 99;  // no such robot
    m.bodies[0].mass = -1;
    m.bodies[0].initial_orientation[0] = 1;
    m.num_joints = 1;
    m.joints.resize(1);
    m.joints[0].name = "Nowhere";
    m.joints[0].body1 = 7;  // no such body
    m.joints[0].body2 = -5;
    nonsense("model_t body of robot 99, joint between bodies 7 and -5", kModel, Encode(m));
  }

  // --- SIM_SENSOR: sensor_reading_t
  bad("sensor_reading_t num_values -1", kSensor, SensorHead(simulation_id).I32(-1).Str("").bytes());
  bad("sensor_reading_t num_values 100001 (bound 100000)", kSensor,
      SensorHead(simulation_id).I32(100001).Str("").bytes());
  {
    RawMessage m(sensor_reading_t::getHash());
    m.I64(1).I64(simulation_id).I64(5).F64(0.005).I32(0).StrLength(0).Zeros(20);
    bad("sensor_reading_t name length 0", kSensor, m.bytes());
  }
  {
    sensor_reading_t r{};
    r.simulation_id = simulation_id;
    r.sensor = 12345;  // no such sensor
    r.name = "Scanner";
    r.num_values = 2;
    r.values = {kNaN, -1e308};
    nonsense("sensor_reading_t sensor 12345, NaN values", kSensor, Encode(r));
  }

  // --- SIM_COMMAND_REPLY: command_reply_t
  bad("command_reply_t reason length 0", kCommandReply, ReplyHead(simulation_id).StrLength(0).Zeros(20).bytes());
  bad("command_reply_t num_previous -1", kCommandReply,
      ReplyHead(simulation_id).Str("").I64(5).I32(-1).Str("").bytes());

  return corpus;
}

}  // namespace simpartner::test_support
