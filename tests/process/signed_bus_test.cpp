// A signed bus (SIMPARTNER_BUS_KEY, common/bus_signing.h) with real
// processes: simpartner-sim and a client holding the key drive the robot
// as on an open bus; a process without the key sends a quit, a command, a
// model of another simulation and a state, and replays a signed command:
// nothing changes, and the sim says why it refused each. With nothing
// configured, the first program makes the user's key and every program
// signs with it: a forged quit, command, model, state, mark and image
// change nothing. On an unsigned bus (SIMPARTNER_BUS_KEY=none) the forged
// quit stops the sim: the test that shows what the key does. A program
// without the key, or with another, is told so.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <stdlib.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/wait.h"
#include "simpartner/channels.h"
#include "simpartner/client/client.h"
#include "simpartner/client/cmd.h"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/image_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/sync_t.hpp"

namespace simpartner {
namespace {

namespace fs = std::filesystem;
using test_support::BusUrl;
using test_support::ShippedWorld;
using test_support::SimProcess;

class SignedBusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : {kBusKeyVariable, "XDG_CONFIG_HOME"})
      if (const char* value = std::getenv(name)) saved_[name] = value;
    dir_ = test_support::FreshTestDir("sp_signed_", 30);
    key_ = (dir_ / "bus.key").string();
    std::ofstream(key_) << std::string(64, 'c') << "\n";
    ::chmod(key_.c_str(), 0600);
  }
  void TearDown() override {
    for (const char* name : {kBusKeyVariable, "XDG_CONFIG_HOME"}) {
      if (saved_.count(name)) ::setenv(name, saved_[name].c_str(), 1);
      else ::unsetenv(name);
    }
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // What a process without the key sends: a quit for any simulation.
  static void ForgeQuit(lcm::LCM& raw) {
    control_t quit{};
    quit.action = control_t::ACTION_QUIT;
    quit.sender = "forger@elsewhere:1";
    raw.publish(channels::kControl, &quit);
  }
  fs::path dir_;
  std::string key_;
  std::map<std::string, std::string> saved_;  // the environment the test changes
};

TEST_F(SignedBusTest, WithoutTheKeyNothingChangesAndAReplayIsRefused) {
  ASSERT_EQ(::setenv(kBusKeyVariable, key_.c_str(), 1), 0);
  const std::string url = BusUrl(1);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, (dir_ / "sim.log").string());
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  EXPECT_NE(sim.Log().find(", signed with " + key_), std::string::npos) << sim.Log();
  client::ClientOptions options;
  options.url = url;
  options.model_timeout = 10;
  client::Client keyed(options);  // reads the key too
  const int64_t simulation = keyed.catalog()->simulation_id();
  // A signed command from the keyed client, seen raw by a process without
  // the key, which keeps the bytes to replay them.
  lcm::LCM raw(url);
  struct Capture {
    std::vector<uint8_t> bytes;
    void On(const lcm::ReceiveBuffer* b, const std::string&) {
      const auto* data = static_cast<const uint8_t*>(b->data);
      bytes.assign(data, data + b->data_size);
    }
  } capture;
  raw.subscribe(channels::kCommand, &Capture::On, &capture);
  std::vector<uint8_t>& captured = capture.bytes;
  const command_reply_t accepted =
      keyed.Command("Axle1Motor", command_t::ACTION_SET, "1000,1");
  EXPECT_TRUE(accepted.accepted) << accepted.reason;
  for (int i = 0; i < 20 && captured.empty(); ++i) raw.handleTimeout(50);
  ASSERT_FALSE(captured.empty());

  // The replay first: the sim names it at once, and the refusals after it
  // within a second only as a count on its next such line.
  raw.publish(channels::kCommand, captured.data(), static_cast<unsigned>(captured.size()));
  ForgeQuit(raw);
  command_t forged_command{};
  forged_command.sender = "forger@elsewhere:1";
  forged_command.target = "Axle1Motor";
  forged_command.action = command_t::ACTION_SET;
  forged_command.text = "1000,-5";
  forged_command.apply_at_step = -1;
  raw.publish(channels::kCommand, &forged_command);
  model_t forged_model = *keyed.model();
  forged_model.simulation_id = simulation + 1;
  raw.publish(channels::kModel, &forged_model);

  // A second later (the most a line a second allows), one more forged quit.
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  ForgeQuit(raw);
  const std::string quit_line =
      "SIM_CONTROL: 72 bytes refused: no signature (this bus is signed: SIMPARTNER_BUS_KEY) "
      "(and 3 more refused since the last report)";
  EXPECT_TRUE(test_support::WaitFor([&] { return sim.Log().find(quit_line) != std::string::npos; },
                                    5.0))
      << sim.Log();
  EXPECT_TRUE(sim.running()) << sim.Log();
  EXPECT_EQ(keyed.catalog()->simulation_id(), simulation);
  const std::string log = sim.Log();
  EXPECT_NE(log.find("SIM_COMMAND: " + std::to_string(captured.size()) +
                     " bytes refused: replayed: "),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("bytes refused: no signature (this bus is signed: SIMPARTNER_BUS_KEY); "),
            std::string::npos)
      << "a refusal within a second of the replay's line was named: " << log;
  const auto status = keyed.WaitForStatus(3.0);
  EXPECT_EQ(status.commands_accepted, 1) << log;  // the forged and the replayed were not
  EXPECT_EQ(status.bad_messages, 5) << log;       // replay, quit, command, model, quit
  keyed.Quit();
  EXPECT_EQ(sim.Wait(std::chrono::seconds(10)), std::optional<int>(0)) << sim.Log();
}

// A program refused by a signed bus is told why, not that no sim is
// there: without the key, simpartner-cmd hears the sim (its messages carry
// signatures) and the sim refuses its pause; with another key it hears
// nothing it can verify.
TEST_F(SignedBusTest, AProgramWithoutTheKeyOrWithAnotherIsToldWhy) {
  ASSERT_EQ(::setenv(kBusKeyVariable, key_.c_str(), 1), 0);
  const std::string url = BusUrl(3);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, (dir_ / "sim.log").string());
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  const std::string other_key = (dir_ / "other.key").string();
  std::ofstream(other_key) << std::string(64, 'd') << "\n";
  ::chmod(other_key.c_str(), 0600);
  auto pause = [&](const std::string& log) {
    return test_support::RunToEnd(
        test_support::BuiltCommand("simpartner-cmd", {"--lcm-url", url, "--timeout", "2", "pause"}),
        (dir_ / log).string(), std::chrono::seconds(30));
  };

  ASSERT_EQ(::setenv(kBusKeyVariable, kNoBusKey, 1), 0);
  const test_support::ProgramRun keyless = pause("keyless.log");
  EXPECT_EQ(keyless.status, client::kCmdNoAnswer) << keyless.output;
  EXPECT_NE(keyless.output.find("no SIM_STATUS confirming 'pause' within 2 s on " + url +
                                "; this bus is signed ("),
            std::string::npos)
      << keyless.output;
  EXPECT_NE(keyless.output.find("messages heard carry a signature) and this program has no key "
                                "(SIMPARTNER_BUS_KEY=none), so the sim refuses what it sends: set "
                                "SIMPARTNER_BUS_KEY to the bus's key file"),
            std::string::npos)
      << keyless.output;

  ASSERT_EQ(::setenv(kBusKeyVariable, other_key.c_str(), 1), 0);
  const test_support::ProgramRun wrong = pause("wrong.log");
  EXPECT_EQ(wrong.status, client::kCmdNoAnswer) << wrong.output;
  EXPECT_NE(wrong.output.find("no sim on " + url + ": no SIM_MODEL within 2 s; "), std::string::npos)
      << wrong.output;
  EXPECT_NE(wrong.output.find("messages heard did not verify with this program's key, and none did: the "
                              "bus uses another key (copy the sim's key file: "
                              "docs/several-machines.md) (SIMPARTNER_BUS_KEY; docs/security.md)"),
            std::string::npos)
      << wrong.output;
  EXPECT_TRUE(sim.running()) << sim.Log();
}

TEST_F(SignedBusTest, OnAnUnsignedBusTheForgedQuitStopsTheSim) {
  ASSERT_EQ(::setenv(kBusKeyVariable, kNoBusKey, 1), 0);
  const std::string url = BusUrl(2);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, (dir_ / "sim.log").string());
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  EXPECT_NE(sim.Log().find("simpartner-sim: the bus is unsigned (SIMPARTNER_BUS_KEY=none)"),
            std::string::npos)
      << sim.Log();
  lcm::LCM raw(url);
  ForgeQuit(raw);
  EXPECT_EQ(sim.Wait(std::chrono::seconds(10)), std::optional<int>(0)) << sim.Log();
}

// With nothing configured (no SIMPARTNER_BUS_KEY, an empty XDG config
// directory), the first program makes the user's key, says where, and
// every program signs with it; simpartner-cmd names the same key. A
// process without it forges a quit, a command, a model of another
// simulation, a state far ahead, a lock-step JOIN and a camera image:
// each is refused at its signature, and nothing changes. (On an unsigned
// bus the same quit stops the sim: OnAnUnsignedBusTheForgedQuitStopsTheSim.)
TEST_F(SignedBusTest, WithNoKeyConfiguredEveryProgramSignsAndForgeriesChangeNothing) {
  const std::string config = (dir_ / "config").string();
  ASSERT_EQ(::setenv("XDG_CONFIG_HOME", config.c_str(), 1), 0);
  ASSERT_EQ(::unsetenv(kBusKeyVariable), 0);
  const std::string made = config + "/simpartner/bus.key";
  const std::string url = BusUrl(4);
  SimProcess sim(ShippedWorld("flat_ground.xml"), url, (dir_ / "sim.log").string());
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  EXPECT_NE(sim.Log().find("simpartner-sim: made the bus key " + made + " (mode 0600)"),
            std::string::npos)
      << sim.Log();
  EXPECT_NE(sim.Log().find(", signed with " + made), std::string::npos) << sim.Log();
  struct stat info {};
  ASSERT_EQ(::stat(made.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  EXPECT_EQ(info.st_size, 65);  // 64 hex digits and a newline
  ASSERT_EQ(::stat((config + "/simpartner").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0077, 0u);
  const test_support::ProgramRun key = test_support::RunToEnd(
      test_support::BuiltCommand("simpartner-cmd", {"key"}), (dir_ / "key.log").string(),
      std::chrono::seconds(30));
  EXPECT_EQ(key.status, 0) << key.output;
  EXPECT_EQ(key.output, made + "\n");  // and no second key made

  client::ClientOptions options;
  options.url = url;
  options.model_timeout = 10;
  client::Client keyed(options);  // the default too: the same key
  const int64_t simulation = keyed.catalog()->simulation_id();
  ASSERT_TRUE(keyed.LatestImage("HeadCamera") == std::nullopt);  // receives images from now on
  const state_t seen = keyed.WaitUntilSimTime(0.2, 10.0);

  lcm::LCM raw(url);
  ForgeQuit(raw);
  command_t command{};
  command.sender = "forger@elsewhere:1";
  command.target = keyed.model()->actuators.at(0).name;
  command.action = command_t::ACTION_HOLD;
  command.apply_at_step = -1;
  raw.publish(channels::kCommand, &command);
  model_t model = *keyed.model();
  model.simulation_id = simulation + 1;
  raw.publish(channels::kModel, &model);
  state_t ahead = seen;
  ahead.step += 1000000;
  ahead.sim_time += 1000.0;
  raw.publish(channels::kState, &ahead);
  sync_t join{};
  join.controller = "forger";
  join.sender = "forger@elsewhere:1";
  join.token = "nonce";
  join.action = sync_t::ACTION_JOIN;
  join.period = 1;
  raw.publish(channels::kSync, &join);
  image_t image{};
  for (const sensor_t& s : keyed.model()->sensors) {
    if (s.name != "HeadCamera") continue;
    image.camera = s.id;
    image.name = s.name;
    image.robot = keyed.model()->robots.at(static_cast<size_t>(s.robot)).name;
    image.width = static_cast<int32_t>(s.params.at(0));
    image.height = static_cast<int32_t>(s.params.at(1));
  }
  ASSERT_EQ(image.width, 640);
  image.simulation_id = simulation;
  image.step = seen.step;
  image.sim_time = seen.sim_time;
  image.format = image_t::FORMAT_RGB8;
  image.data.assign(3u * 640u * 480u, 200);
  image.num_bytes = static_cast<int32_t>(image.data.size());
  raw.publish(channels::kImage, &image);

  // The sim steps on, with no controller to wait for; the client keeps
  // its simulation, its states and no image.
  const state_t later = keyed.WaitUntilSimTime(seen.sim_time + 1.5, 15.0);
  EXPECT_TRUE(sim.running()) << sim.Log();
  const status_t status = keyed.WaitForStatus(3.0);
  EXPECT_TRUE(status.sync_controllers.empty());
  EXPECT_EQ(status.commands_accepted, 0) << sim.Log();
  EXPECT_GE(status.bad_messages, 3) << sim.Log();  // the quit, the command, the JOIN
  EXPECT_EQ(keyed.catalog()->simulation_id(), simulation);
  EXPECT_FALSE(keyed.PendingRestart().has_value());
  EXPECT_LT(later.step, ahead.step);
  EXPECT_FALSE(keyed.LatestImage("HeadCamera").has_value());
  const std::string summary = keyed.BadMessageSummary();
  for (const char* channel : {"SIM_MODEL", "SIM_STATE", "SIM_IMAGE"})
    EXPECT_NE(summary.find(channel), std::string::npos) << channel << " in '" << summary << "'";
  EXPECT_NE(sim.Log().find("SIM_CONTROL: 72 bytes refused: no signature"), std::string::npos)
      << sim.Log();
  keyed.Quit();
  EXPECT_EQ(sim.Wait(std::chrono::seconds(10)), std::optional<int>(0)) << sim.Log();
}

}  // namespace
}  // namespace simpartner
