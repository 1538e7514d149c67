// simpartner-teleop as real processes, no hardware: the test build
// (simpartner-teleop-vpad) attaches an SDL virtual game controller and
// takes its stick and button values from a FIFO this test writes; a real
// simpartner-sim runs on a udpm port of its own (ttl=0). What the robot
// does is read from SIM_STATE, what teleop sends from SIM_COMMAND. The
// keyboard window runs on a private Xvfb with real key presses (xdotool).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/teleop/keyboard_window.h"
#include "simpartner/viewer/xvfb.h"
#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "../support/wait.h"
#include "simpartner/sender.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

using test_support::BuiltCommand;
using test_support::BuiltProgram;
using test_support::BusUrl;
using test_support::ReadText;
using test_support::ShippedWorld;
using test_support::SimProcess;
using test_support::SourceDir;

void Control(const std::string& url, int8_t action) {
  lcm::LCM lcm(url);
  control_t control{};
  control.sender = "teleop_process_test";
  control.action = action;
  ASSERT_EQ(test_support::SignedPublisher().Publish(&lcm, channels::kControl, control), 0);
}

struct SeenCommand {
  command_t command;
  Clock::time_point when;
};

// What the test sees on the bus, decoded as the processes decode it.
class Bus : public test_support::BusListener {
 public:
  explicit Bus(const std::string& url) : BusListener(url) {
    Subscribe<state_t>(channels::kState, [this](const state_t& s) {
      state = s;
      if (model.simulation_id == s.simulation_id) wheel_rates.push_back({s.step, MaxWheelRate()});
    });
    KeepLatest(channels::kModel, &model);
    KeepLatest(channels::kStatus, &status);
    Subscribe<command_t>(channels::kCommand,
                         [this](const command_t& c) { commands.push_back({c, Clock::now()}); });
    Subscribe<command_reply_t>(channels::kCommandReply,
                               [this](const command_reply_t& r) { replies.push_back(r); });
  }
  bool HaveModelAndState() {
    return model.simulation_id != 0 && state.simulation_id == model.simulation_id;
  }
  int Body(const std::string& name) const {
    for (size_t k = 0; k < model.bodies.size(); ++k)
      if (model.bodies[k].name == name) return static_cast<int>(k);
    ADD_FAILURE() << "no body " << name;
    return 0;
  }
  int Joint(const std::string& name) const {
    for (size_t k = 0; k < model.joints.size(); ++k)
      if (model.joints[k].name == name) return static_cast<int>(k);
    ADD_FAILURE() << "no joint " << name;
    return 0;
  }
  double X(const std::string& body) const { return state.bodies[Body(body)].position[0]; }
  double Z(const std::string& body) const { return state.bodies[Body(body)].position[2]; }
  // Heading about +y (left positive) of a body's +x axis.
  double Heading(const std::string& body) const {
    const double* q = state.bodies[Body(body)].orientation;  // w x y z
    const double fx = 1 - 2 * (q[2] * q[2] + q[3] * q[3]);
    const double fz = 2 * (q[1] * q[3] - q[0] * q[2]);
    return std::atan2(-fz, fx);
  }
  double JointPosition(const std::string& joint) const {
    return state.joints[Joint(joint)].position[0];
  }
  // Receives until each joint of `pose` rests at its angle (within
  // `tolerance`, turning slower than 0.05 rad/s): a pose reached in the
  // sim's own time, however slowly a loaded machine runs it. False after
  // `seconds`.
  bool UntilJointsRestAt(const std::map<std::string, double>& pose, double tolerance, double seconds) {
    return Until(
        [&] {
          for (const auto& [joint, angle] : pose) {
            const joint_state_t& j = state.joints[Joint(joint)];
            if (std::abs(j.position[0] - angle) > tolerance || std::abs(j.rate[0]) > 0.05) return false;
          }
          return true;
        },
        seconds);
  }
  // "Hip1 0.29 (0.001 rad/s), ..." for a failure's message.
  std::string JointsText(const std::map<std::string, double>& pose) const {
    std::ostringstream text;
    for (const auto& [joint, angle] : pose)
      text << joint << " " << JointPosition(joint) << " (" << state.joints[Joint(joint)].rate[0]
           << " rad/s; expected " << angle << ") ";
    return text.str();
  }
  double MaxWheelRate() const {
    double rate = 0;
    for (const char* axle : {"Axle1", "Axle2", "Axle3", "Axle4"})
      rate = std::max(rate, std::abs(state.joints[Joint(axle)].rate[0]));
    return rate;
  }

  // The step at which the sim applied `command`, once its reply came.
  std::optional<int64_t> AppliedAt(const command_t& command) const {
    for (const command_reply_t& r : replies)
      if (r.request_id == command.request_id && r.sender == command.sender && r.accepted)
        return r.applied_at_step;
    return std::nullopt;
  }
  // The first step from `from` on whose state had every wheel slower than
  // `rate`, by every state received (not only the newest).
  std::optional<int64_t> FirstStepWheelsBelow(int64_t from, double rate) const {
    for (const auto& [step, fastest] : wheel_rates)
      if (step >= from && fastest < rate) return step;
    return std::nullopt;
  }

  model_t model{};
  state_t state{};
  status_t status{};
  std::vector<SeenCommand> commands;
  std::vector<command_reply_t> replies;
  std::vector<std::pair<int64_t, double>> wheel_rates;  // step, fastest wheel [rad/s]
};

class TeleopProcessTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_teleop_process_"); }
  void TearDown() override {
    if (pad_fd_ >= 0) ::close(pad_fd_);
    teleop_.reset();
    sim_.reset();
    if (!HasFailure()) fs::remove_all(dir_);
  }
  void StartSim(const std::string& url, const std::string& world,
                const std::string& log = "sim.log") {
    sim_ = std::make_unique<SimProcess>(ShippedWorld(world), url, (dir_ / log).string());
  }
  // The test build with its virtual pad, reading the FIFO `pad`.
  void StartVirtualPad(const std::string& url) {
    const std::string fifo = (dir_ / "pad").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Held open for writing (O_RDWR does not wait for a reader), so the
    // reader never sees the end of the script before the test is done.
    pad_fd_ = ::open(fifo.c_str(), O_RDWR | O_CLOEXEC);
    ASSERT_GE(pad_fd_, 0);
    teleop_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{"/usr/bin/env", "SDL_VIDEODRIVER=dummy",
                                 BuiltProgram("simpartner-teleop-vpad"), "--lcm-url", url, "--script", fifo},
        (dir_ / "teleop.log").string());
  }
  void Pad(const std::string& lines) {
    ASSERT_EQ(::write(pad_fd_, lines.data(), lines.size()), static_cast<ssize_t>(lines.size()));
  }
  std::string Log(const std::string& name = "teleop.log") { return ReadText(dir_ / name); }
  bool LogHas(const std::string& text, double seconds, const std::string& name = "teleop.log") {
    return test_support::WaitForText(dir_ / name, text, seconds);
  }
  // Until teleop drives `model` with the pad connected.
  void WaitReady(Bus& bus, const std::string& model) {
    ASSERT_TRUE(bus.Until([&] { return bus.HaveModelAndState(); }, 15)) << Log("sim.log");
    ASSERT_TRUE(LogHas("(" + model + "), mapping", 15)) << Log();
    ASSERT_TRUE(LogHas("controller connected", 5)) << Log();
  }
  // Dead-man held, stick fully forward, until RearChassis is `metres`
  // ahead of where it was (in +x, the robot's heading in these worlds).
  void DriveForward(Bus& bus, double metres, double timeout) {
    const double x0 = bus.X("RearChassis"), z0 = bus.Z("RearChassis");
    Pad("button rightshoulder 1\naxis lefty -1\n");
    ASSERT_TRUE(bus.Until([&] { return bus.X("RearChassis") - x0 >= metres; }, timeout))
        << "moved " << bus.X("RearChassis") - x0 << " m\n" << Log();
    EXPECT_LT(std::abs(bus.Z("RearChassis") - z0), std::max(0.05, 0.1 * metres));  // straight on
  }

  fs::path dir_;
  std::unique_ptr<SimProcess> sim_;
  std::unique_ptr<ChildProcess> teleop_;
  int pad_fd_ = -1;
};

// The most commands one target got in any second of [from, to) (wall
// clock micros), by the utime their sender stamped on them: the time they
// were sent, not when this test got round to reading them.
int MostCommandsOfATargetInASecond(const std::vector<SeenCommand>& commands, int64_t from,
                                   int64_t to, std::string* which) {
  int most = 0;
  for (int64_t start = from; start + 1000000 <= to; start += 50000) {
    std::map<std::string, int> count;
    for (const SeenCommand& c : commands)
      if (c.command.utime >= start && c.command.utime < start + 1000000) ++count[c.command.target];
    for (const auto& [target, n] : count)
      if (n > most) most = n, *which = target;
  }
  return most;
}

// The first velocity command to each wheel motor (Axle1Motor ...) with a
// zero target that teleop stamped at or after `from` (wall clock micros).
std::vector<command_t> WheelStopsSentFrom(const std::vector<SeenCommand>& commands, int64_t from) {
  std::vector<command_t> stops;
  std::set<std::string> seen;
  for (const SeenCommand& c : commands) {
    const command_t& command = c.command;
    const bool wheel = command.target.rfind("Axle", 0) == 0;
    // A velocity command's values: the max forces, then the velocities.
    const size_t axes = command.values.size() / 2;
    bool zero = command.action == command_t::ACTION_SET && axes > 0;
    for (size_t k = axes; k < command.values.size(); ++k) zero &= command.values[k] == 0;
    if (command.utime >= from && wheel && zero && seen.insert(command.target).second)
      stops.push_back(command);
  }
  return stops;
}

TEST_F(TeleopProcessTest, StickDrivesAndSteersDeadmanReleaseStopsTheWheelsSignalExits) {
  const std::string url = BusUrl(1);
  Bus bus(url);
  StartSim(url, "gen1_flat.xml");
  StartVirtualPad(url);
  WaitReady(bus, "WorkPartner gen1");

  // Without the dead-man the stick does nothing.
  const double x_start = bus.X("RearChassis");
  Pad("axis lefty -1\n");
  bus.Pump(1.5);
  EXPECT_LT(std::abs(bus.X("RearChassis") - x_start), 0.02);
  EXPECT_LT(bus.MaxWheelRate(), 0.05);

  const int64_t moving_from = WallMicros();
  DriveForward(bus, 1.0, 15);
  // The shipped gen1 mapping: 2 rad/s at full stick.
  EXPECT_NEAR(bus.MaxWheelRate(), 2.0, 0.2);

  // Stick right: the Turner turns to -0.6 rad and the heading turns right.
  const double heading0 = bus.Heading("RearChassis");
  Pad("axis leftx 1\n");
  ASSERT_TRUE(bus.Until([&] { return std::abs(bus.JointPosition("Turner") + 0.6) < 0.05; }, 5))
      << "Turner at " << bus.JointPosition("Turner");
  // 3 s of sim time, however slowly a loaded machine runs it.
  const double turned_at = bus.state.sim_time;
  ASSERT_TRUE(bus.Until([&] { return bus.state.sim_time >= turned_at + 3; }, 60));
  EXPECT_LT(bus.Heading("RearChassis") - heading0, -0.1) << "heading " << bus.Heading("RearChassis");
  const int64_t moving_to = WallMicros();

  // Never more than 10 commands a second to any actuator, while the input
  // changed and while it did not.
  std::string busiest;
  const int most = MostCommandsOfATargetInASecond(bus.commands, moving_from, moving_to, &busiest);
  EXPECT_LE(most, 10) << busiest;
  EXPECT_GE(most, 8) << busiest;  // and repeated
  EXPECT_EQ(bus.refused().total(), 0u);

  // Release: teleop sends the wheels' stop within its period, and the sim
  // stops them within 0.1 s of sim time of applying it; the Turner held.
  // Measured apart, because the first is wall time (a loaded machine may
  // delay any process) and the second the sim's own physics.
  ASSERT_GT(bus.MaxWheelRate(), 1.0);
  const int64_t released_at = WallMicros();
  Pad("button rightshoulder 0\n");
  ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() < 0.05; }, 5));
  const std::vector<command_t> stops = WheelStopsSentFrom(bus.commands, released_at);
  ASSERT_EQ(stops.size(), 4u) << Log();
  const double reaction = (stops.back().utime - released_at) * 1e-6;
  EXPECT_LE(reaction, 0.5) << "teleop sent the wheels' stop " << reaction << " s after release";
  RecordProperty("deadman_reaction_wall_seconds", std::to_string(reaction));
  int64_t applied = 0;
  ASSERT_TRUE(bus.Until([&] {
    applied = 0;
    for (const command_t& stop : stops) {
      const std::optional<int64_t> step = bus.AppliedAt(stop);
      if (!step) return false;
      applied = std::max(applied, *step);
    }
    return true;
  }, 5));
  const std::optional<int64_t> stopped = bus.FirstStepWheelsBelow(applied, 0.05);
  ASSERT_TRUE(stopped.has_value());
  const double stopped_after = (*stopped - applied) * bus.model.step_size;
  EXPECT_LE(stopped_after, 0.1) << "wheels stopped " << stopped_after << " s (sim) after the stop applied";
  RecordProperty("deadman_stop_sim_seconds", std::to_string(stopped_after));
  const double turner_held = bus.JointPosition("Turner");
  bus.Pump(1.0);
  EXPECT_LT(bus.MaxWheelRate(), 0.05);
  EXPECT_NEAR(bus.JointPosition("Turner"), turner_held, 0.02);
  bool held = false;
  for (const SeenCommand& c : bus.commands)
    held |= c.command.target == "TurnerMotor" && c.command.action == command_t::ACTION_HOLD;
  EXPECT_TRUE(held);

  // Moving again, then SIGTERM: the wheels stop and teleop exits 0.
  Pad("button rightshoulder 1\naxis leftx 0\n");
  ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() > 1.0; }, 5));
  teleop_->Signal(SIGTERM);
  EXPECT_EQ(teleop_->Wait(std::chrono::seconds(3)).value_or(-1), 0) << Log();
  ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() < 0.05; }, 2)) << Log();
  EXPECT_NE(Log().find("SIGTERM: stopping the wheels"), std::string::npos);
}

TEST_F(TeleopProcessTest, UnpluggingTheControllerStopsTheRobot) {
  const std::string url = BusUrl(2);
  Bus bus(url);
  StartSim(url, "gen1_flat.xml");
  StartVirtualPad(url);
  WaitReady(bus, "WorkPartner gen1");
  DriveForward(bus, 0.3, 10);
  Pad("detach\n");
  ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() < 0.05; }, 2)) << Log();
  EXPECT_TRUE(LogHas("controller unplugged", 2));
  const double x = bus.X("RearChassis");
  bus.Pump(1.5);
  EXPECT_NEAR(bus.X("RearChassis"), x, 0.02);
  // Plugged in again with the stick still forward: nothing moves until the
  // dead-man is pressed again (the new device starts released).
  Pad("attach\naxis lefty -1\n");
  ASSERT_TRUE(LogHas("controller connected: SimPartner virtual pad\nteleop", 3) ||
              LogHas("vpad: attached\nteleop: controller connected", 3))
      << Log();
  bus.Pump(1.0);
  EXPECT_LT(bus.MaxWheelRate(), 0.05);
  DriveForward(bus, 0.3, 10);
  // SIGINT while moving: the wheels stop and teleop exits 0.
  teleop_->Signal(SIGINT);
  EXPECT_EQ(teleop_->Wait(std::chrono::seconds(3)).value_or(-1), 0) << Log();
  ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() < 0.05; }, 2)) << Log();
  EXPECT_NE(Log().find("SIGINT: stopping the wheels"), std::string::npos) << Log();
}

TEST_F(TeleopProcessTest, FollowsASimThatIsKilledAndStartedAgainAndAPausedOne) {
  const std::string url = BusUrl(3);
  Bus bus(url);
  StartSim(url, "gen1_flat.xml");
  StartVirtualPad(url);
  WaitReady(bus, "WorkPartner gen1");

  // Paused: only SIM_STATUS comes, once a second; teleop keeps the sim as
  // heard and the robot moves on when it resumes.
  DriveForward(bus, 0.2, 10);
  const size_t before_pause = Log().size();
  Control(url, control_t::ACTION_PAUSE);
  ASSERT_TRUE(bus.Until([&] { return bus.status.run_state == status_t::RUN_PAUSED; }, 3));
  bus.Pump(3.5);
  const std::string during_pause = Log().substr(before_pause);
  EXPECT_NE(during_pause.find("sim paused"), std::string::npos) << during_pause;
  EXPECT_EQ(during_pause.find("not heard"), std::string::npos) << during_pause;
  const double x_paused = bus.X("RearChassis");
  Control(url, control_t::ACTION_RESUME);
  ASSERT_TRUE(bus.Until([&] { return bus.X("RearChassis") > x_paused + 0.2; }, 5)) << Log();

  // Frozen (SIGSTOP): after 0.5 s without a word from it teleop commands
  // zero wheel velocity; when it wakes the dead-man is still held and the
  // robot goes on.
  ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() > 1.0; }, 5));
  const int64_t frozen_at = WallMicros();
  sim_->Signal(SIGSTOP);
  bus.Pump(1.5);
  int64_t first_zero = -1;
  for (const SeenCommand& c : bus.commands) {
    if (c.command.target != "Axle1Motor" || c.command.values.size() != 2) continue;
    if (c.command.utime < frozen_at + 200000)
      continue;  // sent before the freeze (or just after, the period's last)
    if (c.command.values[1] == 0.0) {
      first_zero = c.command.utime;
      break;
    }
  }
  ASSERT_GT(first_zero, 0) << Log();
  const double silent_for = (first_zero - frozen_at) * 1e-6;
  EXPECT_GE(silent_for, 0.45);
  EXPECT_LE(silent_for, 0.75);
  RecordProperty("silence_stop_wall_seconds", std::to_string(silent_for));
  EXPECT_TRUE(LogHas("stopped: sim not heard", 2)) << Log();
  const double x_frozen = bus.X("RearChassis");
  sim_->Signal(SIGCONT);
  ASSERT_TRUE(bus.Until([&] { return bus.X("RearChassis") > x_frozen + 0.2; }, 5)) << Log();

  // Killed: teleop stops (sim not heard) and drives the new one, another
  // generation on the same bus.
  const int64_t first = bus.model.simulation_id;
  sim_->Signal(SIGKILL);
  sim_->Wait(std::chrono::seconds(5));
  EXPECT_TRUE(LogHas("stopped: sim not heard", 3)) << Log();
  StartSim(url, "flat_ground_gen2.xml", "sim2.log");
  ASSERT_TRUE(bus.Until([&] { return bus.model.simulation_id != first && bus.HaveModelAndState(); },
                        15));
  ASSERT_TRUE(LogHas("(WorkPartner gen2), mapping", 15)) << Log();
  DriveForward(bus, 0.5, 15);
}

// gen1 to gen4, each in its world, driven forward 1 m by the stick.
TEST_F(TeleopProcessTest, EveryGenerationDrivesForwardOneMetre) {
  const std::pair<const char*, const char*> generations[] = {
      {"gen1_flat.xml", "WorkPartner gen1"},
      {"flat_ground_gen2.xml", "WorkPartner gen2"},
      {"flat_ground.xml", "WorkPartner gen3"},
      {"gen4_flat.xml", "WorkPartner gen4"}};
  int offset = 10;
  for (const auto& [world, model] : generations) {
    SCOPED_TRACE(world);
    const std::string url = BusUrl(offset++);
    Bus bus(url);
    StartSim(url, world);
    if (pad_fd_ >= 0) ::close(pad_fd_), pad_fd_ = -1;
    fs::remove(dir_ / "pad");
    fs::remove(dir_ / "teleop.log");
    StartVirtualPad(url);
    WaitReady(bus, model);
    const auto start = Clock::now();
    DriveForward(bus, 1.0, 20);
    RecordProperty(std::string(model) + " seconds for 1 m",
                   std::to_string(std::chrono::duration<double>(Clock::now() - start).count()));
    Pad("button rightshoulder 0\n");
    ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() < 0.05; }, 2));
    EXPECT_EQ(bus.refused().total(), 0u);
    teleop_.reset();
    sim_.reset();
  }
}

// The program's offline answers: --check against a world, --list, usage.
TEST_F(TeleopProcessTest, CheckListAndUsageAsAProgram) {
  auto run = [&](std::vector<std::string> args, std::string* output) {
    args.insert(args.begin(), {"/usr/bin/env", "SDL_VIDEODRIVER=dummy", BuiltProgram("simpartner-teleop")});
    test_support::ProgramRun program =
        test_support::RunToEnd(args, (dir_ / "run.log").string(), std::chrono::seconds(20));
    *output = std::move(program.output);
    return program.status;
  };
  std::string out;
  EXPECT_EQ(run({"--check", "--environment", ShippedWorld("gen4_flat.xml")}, &out), 0);
  EXPECT_NE(out.find("workpartner_gen4.map: fits robot WorkPartner (WorkPartner gen4)"),
            std::string::npos)
      << out;
  EXPECT_EQ(run({"--check", "--environment", ShippedWorld("gen1_flat.xml"), "--mapping",
                 SourceDir() + "/teleop/mappings/workpartner_gen3.map"},
                &out),
            1);
  EXPECT_NE(out.find("workpartner_gen3.map:4: the mapping is for model 'WorkPartner gen3'; the "
                     "sim's robots are 'WorkPartner gen1'"),
            std::string::npos)
      << out;
  std::ofstream(dir_ / "bad.map") << "model WorkPartner gen1\nforward RearChassis +x\n"
                                     "deadman rightshoulder\ndrive lefty -2\nwheel Axle9Motor\n";
  EXPECT_EQ(run({"--check", "--environment", ShippedWorld("gen1_flat.xml"), "--mapping",
                 (dir_ / "bad.map").string()},
                &out),
            1);
  EXPECT_NE(out.find("bad.map:5: robot 'WorkPartner' (WorkPartner gen1) has no actuator "
                     "'Axle9Motor'"),
            std::string::npos)
      << out;
  EXPECT_EQ(run({"--list"}, &out), 0);
  EXPECT_NE(out.find("no game controller connected"), std::string::npos) << out;
  EXPECT_EQ(run({"--max-speed", "-1"}, &out), 2);
  EXPECT_NE(out.find("--max-speed: value '-1' is not a number above 0"), std::string::npos) << out;
}

// gen3's buttons: body up and down (hips and knees together), torso left,
// claws open; each press one step of the shipped mapping.
TEST_F(TeleopProcessTest, ButtonsRaiseTheBodyTurnTheTorsoAndOpenTheClaws) {
  const std::string url = BusUrl(5);
  Bus bus(url);
  StartSim(url, "flat_ground.xml");
  StartVirtualPad(url);
  WaitReady(bus, "WorkPartner gen3");
  bus.Pump(1.0);  // settled on its wheels
  const double height0 = bus.state.bodies[bus.Body("RearChassis")].position[1];
  auto press = [&](const std::string& button, int times) {
    for (int k = 0; k < times; ++k) {
      Pad("button " + button + " 1\n");
      bus.Pump(0.25);  // paced as a hand would (the pad shows each line to a pass)
      Pad("button " + button + " 0\n");
      bus.Pump(0.25);
    }
  };
  Pad("button rightshoulder 1\n");
  press("dpup", 3);  // body +0.3: hips +-0.3, knees -+0.6
  const std::map<std::string, double> raised = {{"Hip1", 0.3}, {"Knee1", -0.6}, {"Hip3", -0.3}, {"Knee3", 0.6}};
  EXPECT_TRUE(bus.UntilJointsRestAt(raised, 0.05, 15)) << bus.JointsText(raised);
  // Thigh and calf 0.3 m at 36.87 deg from vertical: straightening each by
  // 0.3 rad lifts the hips by 2 * 0.3 * (cos(0.6435 - 0.3) - cos(0.6435)).
  const double lift = 2 * 0.3 * (std::cos(0.6435 - 0.3) - std::cos(0.6435));
  const double height1 = bus.state.bodies[bus.Body("RearChassis")].position[1];
  EXPECT_NEAR(height1 - height0, lift, 0.03) << "from " << height0 << " to " << height1;
  press("dpdown", 1);
  EXPECT_TRUE(bus.UntilJointsRestAt({{"Hip1", 0.2}}, 0.05, 15)) << bus.JointsText({{"Hip1", 0.2}});
  press("dpleft", 2);  // torso +0.4 rad (to the left)
  press("x", 2);       // claws +0.2: upper up, lower down (open)
  const std::map<std::string, double> turned_open = {
      {"TorsoTurn", 0.4}, {"RightGripUpper", 0.2}, {"RightGripLower", -0.2}, {"LeftGripUpper", 0.2}};
  EXPECT_TRUE(bus.UntilJointsRestAt(turned_open, 0.05, 15)) << bus.JointsText(turned_open);
  // Without the dead-man the buttons do nothing; the pose is held.
  Pad("button rightshoulder 0\n");
  press("dpleft", 2);
  bus.Pump(1.0);
  EXPECT_NEAR(bus.JointPosition("TorsoTurn"), 0.4, 0.05);
  EXPECT_NEAR(bus.JointPosition("Hip1"), 0.2, 0.05);
  EXPECT_EQ(bus.refused().total(), 0u);
}

// The keyboard window on a private X server, with real key presses: space
// held is the dead-man, Up drives, Right steers right; letting go stops.
// The keyboard window's background (keyboard_window.cpp) and a test that it
// shows text on it: centred on the screen, most of its pixels the
// background, and a few thousand white ones (the status and the keys).
constexpr uint32_t kAmber = 0xAA7814;
constexpr uint32_t kGreen = 0x28823C;

bool WindowShows(const viewer::XvfbServer& xvfb, uint32_t background) {
  for (int tries = 0; tries < 20; ++tries) {  // it redraws twice a second
    const viewer::ScreenImage screen = xvfb.ReadScreen();
    const int w = teleop::KeyboardWindow::kWidth, h = teleop::KeyboardWindow::kHeight;
    const int x0 = (screen.width - w) / 2, y0 = (screen.height - h) / 2;
    size_t fill = 0, white = 0;
    for (int y = y0; y < y0 + h; ++y)
      for (int x = x0; x < x0 + w; ++x) {
        const uint32_t p = screen.At(x, y);
        fill += p == background;
        white += p == 0xFFFFFF;
      }
    if (fill > static_cast<size_t>(w * h) / 2 && white > 2000 && white < 40000) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  return false;
}

TEST_F(TeleopProcessTest, KeyboardWindowDrivesWithRealKeyPresses) {
  const std::string url = BusUrl(4);
  Bus bus(url);
  StartSim(url, "gen1_flat.xml");
  viewer::XvfbServer xvfb(1280, 720, (dir_ / "xvfb.log").string(), dir_.string());
  teleop_ = std::make_unique<ChildProcess>(
      test_support::OnDisplay(xvfb.display(),
                              BuiltCommand("simpartner-teleop", {"--input", "keyboard", "--lcm-url", url})),
      (dir_ / "teleop.log").string());
  ASSERT_TRUE(bus.Until([&] { return bus.HaveModelAndState(); }, 15)) << Log("sim.log");
  ASSERT_TRUE(LogHas("keyboard window open", 30)) << Log();  // 10 s was short under load
  ASSERT_TRUE(LogHas("(WorkPartner gen1), mapping", 15)) << Log();
  auto xdotool = [&](const std::vector<std::string>& args) {
    const test_support::ProgramRun run =
        test_support::RunXdotool(xvfb.display(), args, (dir_ / "xdotool.log").string());
    EXPECT_EQ(run.status, 0) << run.output;
  };
  // No window manager: keyboard focus follows the pointer onto the window,
  // which is centred on the screen.
  xdotool({"mousemove", "640", "360"});
  bus.Pump(0.5);

  // The window says it, in the window (no window manager shows a title):
  // white text on amber while the dead-man stops the robot.
  EXPECT_TRUE(WindowShows(xvfb, kAmber)) << Log();

  // Up without space: nothing moves.
  const double x0 = bus.X("RearChassis");
  xdotool({"keydown", "Up"});
  bus.Pump(1.0);
  EXPECT_LT(std::abs(bus.X("RearChassis") - x0), 0.02);
  xdotool({"keydown", "space"});
  ASSERT_TRUE(bus.Until([&] { return bus.X("RearChassis") - x0 > 0.5; }, 10)) << Log();
  EXPECT_TRUE(WindowShows(xvfb, kGreen)) << Log();  // green while it moves
  xdotool({"keydown", "Right"});
  ASSERT_TRUE(bus.Until([&] { return bus.JointPosition("Turner") < -0.4; }, 5))
      << "Turner at " << bus.JointPosition("Turner") << "\n" << Log();
  xdotool({"keyup", "space"});
  ASSERT_TRUE(bus.Until([&] { return bus.MaxWheelRate() < 0.05; }, 2)) << Log();
  xdotool({"keyup", "Up"});
  xdotool({"keyup", "Right"});
  EXPECT_TRUE(LogHas("stopped: dead-man released", 2)) << Log();
  xdotool({"key", "Escape"});
  EXPECT_EQ(teleop_->Wait(std::chrono::seconds(5)).value_or(-1), 0) << Log();
}

}  // namespace
}  // namespace simpartner
