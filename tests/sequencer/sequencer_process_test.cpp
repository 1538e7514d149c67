// simpartner-sequencer as a real process against real simpartner-sim
// processes on real LCM multicast (udpm, ttl=0): the same SIM_STATE stream
// at speed 1 and as fast as possible, a refusal, a killed and a restarted
// sim stop the sequence and the wheels, a wrong file sends nothing, and the
// gen3 pole task ends with the pole on the second pair of cubes, in the
// same final pose as an in-process run of the same commands.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/client/client.h"
#include "simpartner/client/errors.h"
#include "simpartner/client/lock_step.h"
#include "simpartner/command_t.hpp"
#include "simpartner/model/loader.h"
#include "simpartner/model_t.hpp"
#include "simpartner/sequencer/sequence.h"
#include "simpartner/sim/simulation.h"
#include "simpartner/state_t.hpp"
#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/encode.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "../support/wait.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

using test_support::BuiltCommand;
using test_support::BusUrl;
using test_support::ReadText;
using test_support::ShippedWorld;
using test_support::SimProcess;
using test_support::SourceDir;

// What the test sees on the bus: states (bytes without utime and
// simulation id, for comparing runs), the model, and the commands sent.
class Listener : public test_support::BusListener {
 public:
  explicit Listener(const std::string& url, bool keep_all_states)
      : BusListener(url), keep_all_(keep_all_states) {
    Subscribe<state_t>(channels::kState, [this](const state_t& s) { OnState(s); }, 200000);
    Keep(channels::kModel, &models);
    Keep(channels::kCommand, &commands);
  }

  std::map<int64_t, std::vector<uint8_t>> states;
  state_t last_state{};
  int64_t last_step = -1;
  std::vector<model_t> models;
  std::vector<command_t> commands;

 private:
  void OnState(const state_t& s) {
    last_state = s;
    last_step = s.step;
    if (!keep_all_) return;
    state_t copy = s;
    copy.utime = 0;
    copy.simulation_id = 0;
    states[s.step] = test_support::Encode(copy);
  }
  bool keep_all_;
};

class SequencerProcessTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_sequencer_process_"); }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::unique_ptr<SimProcess> StartSim(const std::string& url, const std::string& world,
                                       const std::vector<std::string>& extra, const std::string& log) {
    return std::make_unique<SimProcess>(ShippedWorld(world), url, (dir_ / log).string(), extra);
  }
  std::unique_ptr<ChildProcess> StartSequencer(const std::string& url, const std::string& file,
                                               std::vector<std::string> extra,
                                               const std::string& log = "sequencer.log") {
    std::vector<std::string> args = {file, "--lcm-url", url};
    args.insert(args.end(), extra.begin(), extra.end());
    return std::make_unique<ChildProcess>(BuiltCommand("simpartner-sequencer", args), (dir_ / log).string());
  }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  std::string Log(const std::string& name = "sequencer.log") { return ReadText(dir_ / name); }
  // Waits until the log holds `text`.
  bool LogHas(const std::string& text, double seconds, const std::string& name = "sequencer.log") {
    return test_support::WaitForText(dir_ / name, text, seconds);
  }
  fs::path dir_;
};

// Zero-velocity commands the sequencer sent to the wheel motors when it stopped.
std::set<std::string> StoppedWheels(const std::vector<command_t>& commands) {
  std::set<std::string> wheels;
  for (const command_t& c : commands) {
    if (c.sender.rfind("sequencer", 0) != 0 || c.action != command_t::ACTION_SET) continue;
    if (c.apply_at_step != -1 || c.values.size() != 2 || c.values[1] != 0.0) continue;
    wheels.insert(c.target);
  }
  return wheels;
}

const std::set<std::string> kGen1Wheels = {"Axle1Motor", "Axle2Motor", "Axle3Motor",
                                           "Axle4Motor"};

// Wheel 1 at 1 rad/s for 30 s, then stopped: a sequence still playing, at
// its line 4, when something happens to it.
const char* kLongDrive = R"(<sequence version="2">
  <set target="Axle1Motor">1000,1</set>
  <pause seconds="30"/>
  <set target="Axle1Motor">1000,0</set>
</sequence>
)";

// The sequencer said it stopped at `file`'s line 4 for `reason` and sent
// every wheel motor zero velocity (seen on the bus).
void ExpectStoppedAtLineFourWithTheWheelsStopped(Listener& bus, const std::string& log,
                                                 const std::string& file,
                                                 const std::string& reason) {
  EXPECT_NE(log.find(file + ":4: stopped: " + reason), std::string::npos) << log;
  EXPECT_NE(log.find("sent zero velocity to 4 wheel motor(s)"), std::string::npos) << log;
  bus.Pump(0.3);
  EXPECT_EQ(StoppedWheels(bus.commands), kGen1Wheels);
}

// The original's format, unchanged: ports of workpartner_gen1.xml, pauses
// on port 0.
const char* kVersionOneDrive = R"(<?xml version="1.0"?>
<sequence version="1">
  <command><commandString>1000,0.2,100,100,0</commandString><port>1032</port></command>
  <command><commandString>0.3</commandString><port>0</port></command>
  <repeat count="2">
    <command><commandString>1000,1000,100,0,0,2</commandString><port>1028</port></command>
    <command><commandString>1000,1000,100,0,0,2</commandString><port>1029</port></command>
    <command><commandString>1000,1000,100,0,0,2</commandString><port>1030</port></command>
    <command><commandString>1000,1000,100,0,0,2</commandString><port>1031</port></command>
    <command><commandString>0.25</commandString><port>0</port></command>
    <command><commandString>1000,1000,100,0,0,0</commandString><port>1028</port></command>
    <command><commandString>1000,1000,100,0,0,0</commandString><port>1031</port></command>
    <command><commandString>0.1</commandString><port>0</port></command>
  </repeat>
</sequence>
)";

// The test paces each sim: a lock-step controller of its own, a tick every
// 20 steps, answered once the listener has read the tick's state. At speed
// 0 the sim published 1,200 states in a fraction of a second, more than the
// listener's socket buffer holds while its thread gets no CPU: on a loaded
// machine it lost every state after step 582, in CI 103 at speed 1. Paced,
// the sim is at most 20 states (about 180 KB) ahead of the listener.
// `start` is called once the pacer has joined the paused sim.
void PaceUntilTheSimEnds(const std::string& url, Listener* bus, const std::function<void()>& start) {
  client::ClientOptions options;
  options.url = url;
  options.program = "pacer";
  options.model_timeout = 30;
  client::Client pacer(options);
  client::LockStepOptions pace;
  pace.period = 20;
  pace.resume = false;  // the sequencer resumes the paused sim
  pace.timeout = 30;
  client::LockStep loop(pacer, pace);
  start();
  try {
    loop.Next();  // the paused sim's own step, where it waits for the sequencer
    for (;;) {
      const int64_t tick = loop.Next().step;
      ASSERT_TRUE(bus->Until([&] { return bus->last_step >= tick; }, 30))
          << "the listener did not read the state of tick " << tick;
    }
  } catch (const client::SimStopped&) {
    // The sim's duration: the run's end.
  }
}

TEST_F(SequencerProcessTest, SameStateStreamAtSpeedOneAndAsFastAsPossible) {
  const std::string file = Write("drive.xml", kVersionOneDrive);
  constexpr int64_t kLast = 1000;  // the sequence lasts 0.3 + 2 x 0.35 s
  std::map<int64_t, std::vector<uint8_t>> runs[2];
  const char* speeds[2] = {"1", "0"};
  for (int run = 0; run < 2; ++run) {
    const std::string url = BusUrl(1 + run);
    Listener bus(url, true);
    auto sim = StartSim(url, "gen1_flat.xml",
                        {"--startPaused=1", std::string("--speed=") + speeds[run], "--duration=1.2"},
                        "sim" + std::to_string(run) + ".log");
    std::unique_ptr<ChildProcess> sequencer;
    PaceUntilTheSimEnds(url, &bus, [&] {
      sequencer = StartSequencer(url, file, {"--from-zero", "--resume"},
                                 "sequencer" + std::to_string(run) + ".log");
    });
    ASSERT_TRUE(sequencer) << Log("sim" + std::to_string(run) + ".log");
    const std::optional<int> status = sequencer->Wait(std::chrono::seconds(30));
    ASSERT_EQ(status, std::optional<int>(0)) << Log("sequencer" + std::to_string(run) + ".log");
    ASSERT_EQ(sim->Wait(std::chrono::seconds(30)), std::optional<int>(0));
    bus.Pump(0.3);
    // Progress lines name the file line and the sim time of each command.
    const std::string log = Log("sequencer" + std::to_string(run) + ".log");
    EXPECT_NE(log.find("t=0.300 s  line 6: set Axle1Motor"), std::string::npos) << log;
    EXPECT_NE(log.find("t=0.650 s  line 6: set Axle1Motor"), std::string::npos) << log;
    runs[run] = std::move(bus.states);
  }
  // Every state of the sequence, the same in both runs.
  for (int64_t step = 1; step <= kLast; ++step) {
    ASSERT_TRUE(runs[0].count(step) && runs[1].count(step)) << "no SIM_STATE of step " << step;
    ASSERT_EQ(runs[0][step], runs[1][step]) << "SIM_STATE of step " << step << " differs";
  }
  // The commands took effect: the robot drove (wheels at 2 rad/s x 0.235 m).
  state_t first, last;
  const std::vector<uint8_t>& first_bytes = runs[0][1];
  const std::vector<uint8_t>& last_bytes = runs[0][kLast];
  first.decode(first_bytes.data(), 0, static_cast<int>(first_bytes.size()));
  last.decode(last_bytes.data(), 0, static_cast<int>(last_bytes.size()));
  double moved = 0;
  for (size_t b = 0; b < first.bodies.size(); ++b)
    moved = std::max(moved, std::abs(last.bodies[b].position[0] - first.bodies[b].position[0]));
  EXPECT_GT(moved, 0.1);
}

TEST_F(SequencerProcessTest, RefusalStopsTheSequenceAndTheWheels) {
  const std::string url = BusUrl(3);
  Listener bus(url, false);
  auto sim = StartSim(url, "gen1_flat.xml", {"--duration=30"}, "sim.log");
  const std::string file = Write("refused.xml", R"(<sequence version="2">
  <set target="Axle1Motor">1000,1</set>
  <pause seconds="2"/>
  <set target="Axle2Motor">1000,5000</set>
  <pause seconds="5"/>
</sequence>
)");
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(bus.Until([&] { return sequencer->Wait(std::chrono::milliseconds(0)).has_value(); }, 20));
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(0)), std::optional<int>(1));
  bus.Pump(0.3);
  const std::string log = Log();
  EXPECT_NE(log.find(file + ":4: stopped: set Axle2Motor '1000,5000' refused by the sim: "),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("velocity"), std::string::npos) << log;  // the sim's reason names the value
  EXPECT_NE(log.find("line 2: set Axle1Motor"), std::string::npos) << log;
  EXPECT_NE(log.find("sent zero velocity to 4 wheel motor(s)"), std::string::npos) << log;
  EXPECT_EQ(StoppedWheels(bus.commands), kGen1Wheels);
}

TEST_F(SequencerProcessTest, KilledSimStopsTheSequenceWithinTwoSecondsOfSilence) {
  const std::string url = BusUrl(4);
  Listener bus(url, false);
  auto sim = StartSim(url, "gen1_flat.xml", {"--duration=60"}, "sim.log");
  const std::string file = Write("long.xml", kLongDrive);
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(LogHas("line 2: set Axle1Motor", 10)) << Log();
  sim->Signal(SIGKILL);
  const auto killed = Clock::now();
  const std::optional<int> status = sequencer->Wait(std::chrono::seconds(10));
  const double took = std::chrono::duration<double>(Clock::now() - killed).count();
  ASSERT_EQ(status, std::optional<int>(1)) << Log();
  EXPECT_GE(took, 1.9);
  EXPECT_LT(took, 4.0);
  ExpectStoppedAtLineFourWithTheWheelsStopped(
      bus, Log(), file, "the sim went silent: nothing on SIM_STATE or SIM_STATUS for 2.0 s");
}

// SIGTERM or SIGINT (a supervisor, Ctrl-C) stops the sequence as a
// refusal does: the line it was at, the wheels to zero, exit 1. Before, the
// sequencer died at once and left the robot driving.
TEST_F(SequencerProcessTest, SigtermAndSigintStopTheSequenceAndTheWheels) {
  for (const int signal : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(signal == SIGTERM ? "SIGTERM" : "SIGINT");
    const std::string url = BusUrl(signal == SIGTERM ? 13 : 14);
    Listener bus(url, false);
    auto sim = StartSim(url, "gen1_flat.xml", {"--duration=60"}, "sim.log");
    const std::string file = Write("long.xml", kLongDrive);
    auto sequencer = StartSequencer(url, file, {});
    ASSERT_TRUE(LogHas("line 2: set Axle1Motor", 10)) << Log();
    sequencer->Signal(signal);
    const std::optional<int> status = sequencer->Wait(std::chrono::seconds(5));
    ASSERT_EQ(status, std::optional<int>(1)) << Log();
    ExpectStoppedAtLineFourWithTheWheelsStopped(bus, Log(), file,
                                                "interrupted (SIGINT or SIGTERM)");
    sim->Stop(std::chrono::seconds(5));
  }
}

TEST_F(SequencerProcessTest, RestartedSimStopsTheSequence) {
  const std::string url = BusUrl(5);
  Listener bus(url, false);
  auto sim = StartSim(url, "gen1_flat.xml", {"--duration=60"}, "sim.log");
  const std::string file = Write("long.xml", kLongDrive);
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(LogHas("line 2: set Axle1Motor", 10)) << Log();
  sim->Signal(SIGKILL);
  sim->Wait(std::chrono::seconds(5));
  auto restarted = StartSim(url, "gen1_flat.xml", {"--duration=60"}, "sim2.log");
  ASSERT_TRUE(bus.Until([&] { return sequencer->Wait(std::chrono::milliseconds(0)).has_value(); }, 15))
      << Log();
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(0)), std::optional<int>(1));
  ExpectStoppedAtLineFourWithTheWheelsStopped(bus, Log(), file,
                                              "the sim restarted under the sequence");
}

// The issue's attack: 20 forged SIM_MODELs with other simulation ids (a
// stale sim elsewhere, a replayed log) while a sequence plays. Before, the
// sequencer stopped ("the sim restarted under the sequence") and under
// scripts/run played again from line 1; now it plays on. On an unsigned
// bus, where a key does not refuse them first.
TEST_F(SequencerProcessTest, ForgedModelsOfOtherSimulationsDoNotStopTheSequence) {
  const test_support::UnsignedBus unsigned_bus;
  const std::string url = BusUrl(12);
  Listener bus(url, false);
  auto sim = StartSim(url, "gen1_flat.xml", {"--duration=60"}, "sim.log");
  const std::string file = Write("long.xml", kLongDrive);
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(LogHas("line 2: set Axle1Motor", 10)) << Log();
  ASSERT_TRUE(bus.Until([&] { return !bus.models.empty(); }, 5));
  for (int i = 0; i < 20; ++i) {
    model_t forged = bus.models.front();
    forged.simulation_id = 777000 + i;
    forged.sender = "simpartner-sim@elsewhere:" + std::to_string(i);
    bus.lcm().publish(channels::kModel, &forged);
    bus.Pump(0.05);
  }
  bus.Pump(2.0);
  EXPECT_FALSE(sequencer->Wait(std::chrono::milliseconds(0)).has_value()) << Log();
  EXPECT_EQ(Log().find("restarted"), std::string::npos) << Log();
  sequencer->Signal(SIGTERM);
  sequencer->Wait(std::chrono::seconds(10));
  sim->Stop(std::chrono::seconds(5));
}

TEST_F(SequencerProcessTest, WrongFileAgainstTheBusModelSendsNothing) {
  const std::string url = BusUrl(6);
  Listener bus(url, false);
  auto sim = StartSim(url, "gen1_flat.xml", {"--duration=30"}, "sim.log");
  // gen1 has no scanner and no port 1041 (gen3's TorsoTurnMotor).
  const std::string file = Write("wrong.xml", R"(<sequence version="2">
  <set target="Axle1Motor">1000,1</set>
  <set port="1041">1000,0.1,10,0,0</set>
  <wait sensor="Scanner" below="1" timeout="10"/>
</sequence>
)");
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(bus.Until([&] { return sequencer->Wait(std::chrono::milliseconds(0)).has_value(); }, 15));
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(0)), std::optional<int>(2));
  const std::string log = Log();
  EXPECT_NE(log.find(file + ":3: set: port 1041 is not an actuator or sensor of the model"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find(file + ":4: wait: 'Scanner' is not an actuator or sensor of the model"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("nothing was sent"), std::string::npos) << log;
  bus.Pump(0.3);
  EXPECT_TRUE(bus.commands.empty()) << bus.commands.size() << " commands on the bus";
}

TEST_F(SequencerProcessTest, NoSimOnTheBus) {
  const std::string url = BusUrl(7);
  const std::string file = Write("one.xml", R"(<sequence version="2">
  <set target="Axle1Motor">1000,1</set>
</sequence>
)");
  auto sequencer = StartSequencer(url, file, {"--model-timeout", "0.5"});
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(10)), std::optional<int>(3)) << Log();
  EXPECT_NE(Log().find(file + ": not played: "), std::string::npos) << Log();
}

int JointIndex(const model_t& model, const std::string& name) {
  for (size_t j = 0; j < model.joints.size(); ++j)
    if (model.joints[j].name == name) return static_cast<int>(j);
  return -1;
}

TEST_F(SequencerProcessTest, WaitsForAJointAngleThenGoesOn) {
  const std::string url = BusUrl(9);
  Listener bus(url, true);
  auto sim = StartSim(url, "gen1_flat.xml", {"--duration=30"}, "sim.log");
  const std::string file = Write("wait.xml", R"(<sequence version="2">
  <set target="TurnerMotor">1000,0.2,100,100,0</set>
  <wait joint="Turner" angle="0.2" tolerance="0.002" timeout="5"/>
  <comment>steered</comment>
  <set target="Axle1Motor">1000,1</set>
  <pause seconds="0.2"/>
</sequence>
)");
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(bus.Until([&] { return sequencer->Wait(std::chrono::milliseconds(0)).has_value(); }, 20));
  ASSERT_EQ(sequencer->Wait(std::chrono::seconds(0)), std::optional<int>(0)) << Log();
  const std::string log = Log();
  const std::string met = "line 3: joint Turner within 0.002 of 0.2: met at step ";
  const size_t at = log.find(met);
  ASSERT_NE(at, std::string::npos) << log;
  const int64_t met_step = std::stoll(log.substr(at + met.size()));
  EXPECT_NE(log.find("line 4: # steered"), std::string::npos) << log;
  EXPECT_NE(log.find("line 5: set Axle1Motor"), std::string::npos) << log;
  // The state of that step has the joint there; the wheel command came after.
  ASSERT_FALSE(bus.models.empty());
  const int turner = JointIndex(bus.models.back(), "Turner");
  ASSERT_GE(turner, 0);
  const auto state = bus.states.find(met_step);
  ASSERT_NE(state, bus.states.end());
  state_t s;
  s.decode(state->second.data(), 0, static_cast<int>(state->second.size()));
  EXPECT_NEAR(s.joints[static_cast<size_t>(turner)].position[0], 0.2, 0.002);
  bool after = false;
  for (const command_t& c : bus.commands)
    if (c.target == "Axle1Motor") after = c.apply_at_step > met_step;
  EXPECT_TRUE(after);
}

TEST_F(SequencerProcessTest, WaitThatTimesOutStopsTheSequence) {
  const std::string url = BusUrl(10);
  Listener bus(url, false);
  auto sim = StartSim(url, "gen1_flat.xml", {"--duration=30"}, "sim.log");
  const std::string file = Write("timeout.xml", R"(<sequence version="2">
  <set target="Axle1Motor">1000,1</set>
  <wait joint="Turner" angle="1" tolerance="0.001" timeout="0.5"/>
  <set target="Axle1Motor">1000,2</set>
</sequence>
)");
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(bus.Until([&] { return sequencer->Wait(std::chrono::milliseconds(0)).has_value(); }, 20));
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(0)), std::optional<int>(1));
  const std::string log = Log();
  EXPECT_NE(log.find(file + ":3: stopped: wait for joint Turner within 0.001 of 1: not met within "
                            "0.500 s of sim time"),
            std::string::npos)
      << log;
  bus.Pump(0.3);
  EXPECT_EQ(StoppedWheels(bus.commands), kGen1Wheels);
}

// gen2 stands 6 m from a wall (scanner_wall.xml): the scanner's middle
// ray reads 5.335 m (SPEC 8).
TEST_F(SequencerProcessTest, WaitsForAScannerReading) {
  const std::string url = BusUrl(11);
  Listener bus(url, false);
  auto sim = StartSim(url, "scanner_wall.xml", {"--duration=30"}, "sim.log");
  const std::string file = Write("scan.xml", R"(<sequence version="2">
  <wait sensor="Scanner" index="5" below="5.4" timeout="2"/>
  <wait sensor="Scanner" index="5" above="5.3" timeout="2"/>
  <wait sensor="Scanner" index="5" below="5.0" timeout="0.3"/>
</sequence>
)");
  auto sequencer = StartSequencer(url, file, {});
  ASSERT_TRUE(bus.Until([&] { return sequencer->Wait(std::chrono::milliseconds(0)).has_value(); }, 20));
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(0)), std::optional<int>(1)) << Log();
  const std::string log = Log();
  EXPECT_NE(log.find("line 2: sensor Scanner value 5 below 5.4: met at step"), std::string::npos) << log;
  EXPECT_NE(log.find("line 3: sensor Scanner value 5 above 5.3: met at step"), std::string::npos) << log;
  EXPECT_NE(log.find(file + ":4: stopped: wait for sensor Scanner value 5 below 5: not met within "
                            "0.300 s of sim time"),
            std::string::npos)
      << log;
}

// The validation's pole task, as shipped, through the sequencer process
// against a real sim as fast as possible.
TEST_F(SequencerProcessTest, PoleTaskEndsWithThePoleOnTheSecondPairOfCubes) {
  constexpr double kDuration = 19.0;  // the sequence ends at 18.6 s
  const int64_t last_step = std::llround(kDuration / 0.001);
  const std::string url = BusUrl(8);
  Listener bus(url, false);
  auto sim = StartSim(url, "pole_task.xml",
                      {"--startPaused=1", "--speed=0", "--duration=" + std::to_string(kDuration)},
                      "sim.log");
  auto sequencer = StartSequencer(url, SourceDir() + "/sequences/gen3_pole_task.xml",
                                  {"--from-zero", "--resume", "--quiet"});
  ASSERT_TRUE(bus.Until([&] { return bus.last_step >= last_step; }, 240)) << Log();
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(10)), std::optional<int>(0)) << Log();
  ASSERT_EQ(sim->Wait(std::chrono::seconds(10)), std::optional<int>(0)) << Log("sim.log");
  ASSERT_FALSE(bus.models.empty());
  const model_t& model = bus.models.back();
  int pole = -1;
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (model.bodies[b].name == "Pole") pole = static_cast<int>(b);
  ASSERT_GE(pole, 0);
  ASSERT_EQ(bus.last_state.step, last_step);
  const body_state_t& p = bus.last_state.bodies[static_cast<size_t>(pole)];
  // pole_task.xml: the second pair of 1 m cubes is centred at x 4.2; the
  // pole (r 0.05 m) rests on their tops at 1.05 m, still.
  EXPECT_NEAR(p.position[1], 1.05, 0.005);
  EXPECT_NEAR(p.position[0], 4.2, 0.5);
  EXPECT_LT(std::hypot(p.linear_velocity[0], p.linear_velocity[1], p.linear_velocity[2]), 0.001);

  // The same commands through the sim library in this process, each in
  // the step the file gives it (as simpartner-validate runs them): the
  // same final pose of every body.
  const sequencer::SequenceParseResult parsed =
      sequencer::LoadSequenceFile(SourceDir() + "/sequences/gen3_pole_task.xml");
  ASSERT_TRUE(parsed.sequence);
  Parameters params;
  params.environment = ShippedWorld("pole_task.xml");
  sim::Simulation local(model::LoadWorldOrThrow(params.environment), params, 1);
  int64_t id = 0;
  for (const sequencer::Command& c : parsed.sequence->segments.at(0).commands) {
    command_t m{};
    m.request_id = ++id;
    m.sender = "test";
    m.target = c.target;
    m.action = c.action;
    m.apply_at_step = std::llround(c.time / 0.001);
    m.text = c.text;
    const std::optional<command_reply_t> refused = local.Submit(m);
    ASSERT_FALSE(refused.has_value()) << c.line << ": " << refused->reason;
  }
  while (local.step() < last_step) {
    ASSERT_TRUE(local.Step());
    local.TakeReplies();
    local.TakeSensorReadings();
  }
  state_t mine{};
  local.FillState(&mine);
  ASSERT_EQ(mine.bodies.size(), bus.last_state.bodies.size());
  for (size_t b = 0; b < mine.bodies.size(); ++b) {
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(mine.bodies[b].position[k], bus.last_state.bodies[b].position[k], 1e-9)
          << model.bodies[b].name;
  }
}

}  // namespace
}  // namespace simpartner
