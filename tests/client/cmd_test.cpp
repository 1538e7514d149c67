// simpartner-cmd against a real sim: each outcome has its exit status and
// a message saying which (accepted, refused and why, no answer, usage,
// unknown name). RunCmd in-process for most, the real binary for the
// shell commands of docs/driving.md.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <fstream>
#include <sstream>
#include <thread>

#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "simpartner/client/client.h"
#include "simpartner/channels.h"
#include "simpartner/client/cmd.h"
#include "simpartner/control_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner::client {
namespace {

using test_support::BuiltCommand;
using test_support::ReadText;
using test_support::RunToEnd;
using test_support::ShippedWorld;
using test_support::SimProcess;
using test_support::FreshTestDir;
using test_support::BusUrl;

struct CmdResult {
  int status;
  std::string out, err;
};

CmdResult RunInProcess(std::vector<std::string> args) {
  std::ostringstream out, err;
  const int status = RunCmd(args, out, err);
  return {status, out.str(), err.str()};
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class CmdTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = FreshTestDir("sp_client_");
  }
  void TearDown() override {
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }
  std::filesystem::path dir_;
};

TEST_F(CmdTest, OutcomesAndExitStatuses) {
  const std::string url = BusUrl(11);
  SimProcess sim(ShippedWorld("scanner_wall.xml"), url, (dir_ / "sim.log").string());
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  auto cmd = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"--lcm-url", url});
    return RunInProcess(args);
  };
  CmdResult r = cmd({"set", "Axle1Motor", "300,1.0"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "Axle1Motor: accepted, applied at step ")) << r.out;
  EXPECT_TRUE(Contains(r.out, "(was 0,0,1000)")) << r.out;

  // By legacy port, and the three-slot form of the original.
  r = cmd({"set", "1029", "1000,1000,100,0,0,0.2"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "Axle2Motor: accepted")) << r.out;

  r = cmd({"set", "Axle1Motor", "300,1e9"});
  EXPECT_EQ(r.status, kCmdRefused);
  EXPECT_TRUE(Contains(r.err, "simpartner-cmd: Axle1Motor: refused by the sim: ")) << r.err;
  EXPECT_TRUE(Contains(r.err, "1000000000")) << r.err;

  r = cmd({"set", "Axle1Mottor", "300,1"});
  EXPECT_EQ(r.status, kCmdUnknownName);
  EXPECT_TRUE(Contains(r.err, "did you mean 'Axle1Motor'")) << r.err;

  // Wrong count: refused before sending (usage), naming the forms.
  r = cmd({"set", "Axle1Motor", "300,1,2"});
  EXPECT_EQ(r.status, kCmdUsage);
  EXPECT_TRUE(Contains(r.err, "fmax,vel (2)")) << r.err;
  r = cmd({"set", "Axle1Motor", "300,fast"});
  EXPECT_EQ(r.status, kCmdUsage);
  EXPECT_TRUE(Contains(r.err, "values[1] = 'fast'")) << r.err;

  r = cmd({"hold", "TurnerMotor", "800"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  r = cmd({"stops", "TurnerMotor", "-0.5,0.5"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  r = cmd({"stops", "TurnerMotor", "0.5,-0.5"});
  EXPECT_EQ(r.status, kCmdRefused) << r.err;

  r = cmd({"read", "Scanner"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "Scanner (scanner) step ")) << r.out;
  r = cmd({"read", "Axle1Motor"});
  EXPECT_EQ(r.status, kCmdUnknownName) << r.err;

  r = cmd({"model"});
  EXPECT_EQ(r.status, kCmdOk);
  EXPECT_TRUE(Contains(r.out, "robot WorkPartner (WorkPartner gen2)")) << r.out;
  EXPECT_TRUE(Contains(r.out, "Axle1Motor  velocity controller, port 1028, joint Axle1")) << r.out;
  EXPECT_TRUE(Contains(r.out, "Scanner  scanner, port 1027")) << r.out;

  r = cmd({"state", "--body", "Torso"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "Torso position ")) << r.out;
  r = cmd({"state", "--body", "Torsoo"});
  EXPECT_EQ(r.status, kCmdUnknownName);
  r = cmd({"state", "--follow", "--count", "3"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  size_t lines = 0;
  for (size_t p = r.out.find("step "); p != std::string::npos; p = r.out.find("\nstep ", p + 1))
    ++lines;
  EXPECT_EQ(lines, 3u) << r.out;

  r = cmd({"pause"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "sim paused")) << r.out;
  r = cmd({"step", "25"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  r = cmd({"--timeout", "0.5", "set", "Axle1Motor", "300,0"});
  EXPECT_EQ(r.status, kCmdNoAnswer);
  EXPECT_TRUE(Contains(r.err, "the sim is paused")) << r.err;
  r = cmd({"resume"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "sim running")) << r.out;
  r = cmd({"speed", "0"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "as fast as possible")) << r.out;
  r = cmd({"status"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "running, step ")) << r.out;
  EXPECT_TRUE(Contains(r.out, ", engine ode, ")) << r.out;  // the sim's default engine
  r = cmd({"reset"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "sim reset: simulation ")) << r.out;
  r = cmd({"quit"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "sim stopped")) << r.out;
  EXPECT_TRUE(sim.Wait(std::chrono::seconds(10)).has_value());
}

// A paused sim sends no SIM_STATE; it answers a state request.
TEST_F(CmdTest, AStateOfAPausedSim) {
  const std::string url = BusUrl(13);
  SimProcess sim(ShippedWorld("gen4_flat.xml"), url, (dir_ / "sim.log").string(),
                 {"--startPaused=1"});
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  auto cmd = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"--lcm-url", url});
    return RunInProcess(args);
  };
  CmdResult r = cmd({"state", "--body", "FrontChassis"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "step 0, t = 0 s")) << r.out;
  EXPECT_TRUE(Contains(r.out, "FrontChassis position ")) << r.out;
  r = cmd({"step", "5"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  r = cmd({"state"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_TRUE(Contains(r.out, "step 5, t = 0.005 s")) << r.out;
  EXPECT_TRUE(Contains(r.out, "joint Turner position ")) << r.out;
}

// The sim keeps its recent warnings in every status: a reply to a control
// says a warning once, not again in each later reply.
TEST_F(CmdTest, RepliesDoNotRepeatOldWarnings) {
  const std::string url = BusUrl(14);
  SimProcess sim(ShippedWorld("gen4_flat.xml"), url, (dir_ / "sim.log").string());
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  auto cmd = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"--lcm-url", url});
    return RunInProcess(args);
  };
  // A pause meant for another simulation: the sim refuses it and warns
  // ("bus: SIM_CONTROL: action 0 from 'elsewhere' is for simulation_id 42").
  lcm::LCM bus(url);
  test_support::SignedPublisher publisher;
  control_t stray{};
  stray.simulation_id = 42;
  stray.sender = "elsewhere";
  stray.action = control_t::ACTION_PAUSE;
  publisher.Publish(&bus, channels::kControl, stray);
  const std::string warning = "from 'elsewhere' is for simulation_id 42";
  CmdResult r;
  for (int tries = 0; tries < 20 && !Contains(r.out, warning); ++tries) r = cmd({"status"});
  ASSERT_TRUE(Contains(r.out, warning)) << r.out;  // the status lists it
  r = cmd({"pause"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_FALSE(Contains(r.out, warning)) << r.out;
  // At least that one: a loaded machine adds "behind real time" warnings.
  EXPECT_TRUE(Contains(r.out, "earlier warning") &&
              Contains(r.out, " not repeated: simpartner-cmd status lists them)"))
      << r.out;
  r = cmd({"resume"});
  EXPECT_FALSE(Contains(r.out, warning)) << r.out;
}

// status prints the engine SIM_STATUS names; a status without one comes
// from a sim older than the field, and every such sim ran ODE.
TEST_F(CmdTest, StatusNamesThePhysicsEngine) {
  const std::string url = BusUrl(15);
  lcm::LCM bus(url);
  ASSERT_TRUE(bus.good());
  test_support::SignedPublisher publisher;
  for (const auto& [engine, printed] : std::vector<std::pair<std::string, std::string>>{
           {"mujoco", ", engine mujoco, "}, {"", ", engine ode, "}}) {
    status_t status{};
    status.simulation_id = 77;
    status.host = "elsewhere";
    status.engine = engine;
    status.run_state = status_t::RUN_RUNNING;
    // A sim's status stream (cmd prints one sent after it started listening).
    std::atomic<bool> done{false};
    std::thread sim([&] {
      while (!done) {
        publisher.Publish(&bus, channels::kStatus, status);
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    });
    const CmdResult r = RunInProcess({"--lcm-url", url, "--timeout", "10", "status"});
    done = true;
    sim.join();
    EXPECT_EQ(r.status, kCmdOk) << r.err;
    EXPECT_TRUE(Contains(r.out, "simulation 77 on elsewhere" + printed)) << r.out;
  }
}

// Two sims on one bus: a control reaches only the sim the command is
// attached to, the one whose SIM_STATUS it heard first or the one --sim
// names, and the other keeps running (one quit once stopped two
// sims). The sims send their model once a minute, so the command hears
// none, as one started between two models does: before, its control then
// carried simulation id 0, which every sim obeys.
TEST_F(CmdTest, ControlReachesOnlyTheSimItIsAttachedTo) {
  const std::string url = BusUrl(15);
  test_support::BusListener bus(url);
  std::vector<status_t> statuses;
  bus.Keep(channels::kStatus, &statuses);
  const std::vector<std::string> flags = {"--modelPeriod=60", "--allow-other-sims"};
  SimProcess first(ShippedWorld("gen1_flat.xml"), url, (dir_ / "first.log").string(), flags);
  ASSERT_TRUE(first.WaitUntilRunning(30)) << first.Log();
  ASSERT_TRUE(bus.Until([&] { return !statuses.empty(); }, 5.0));
  const int64_t first_id = statuses.front().simulation_id;
  SimProcess second(ShippedWorld("gen1_flat.xml"), url, (dir_ / "second.log").string(), flags);
  ASSERT_TRUE(second.WaitUntilRunning(30)) << second.Log();
  int64_t second_id = 0;
  ASSERT_TRUE(bus.Until([&] {
    for (const status_t& s : statuses) if (s.simulation_id != first_id) second_id = s.simulation_id;
    return second_id != 0;
  }, 5.0));
  auto cmd = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"--lcm-url", url});
    return RunInProcess(args);
  };
  // The next two statuses of `id` from statuses[from] on, each in `run_state`.
  auto two_from = [&](size_t from, int64_t id, int run_state) {
    size_t seen = 0, matching = 0;
    bus.Until([&] {
      seen = matching = 0;
      for (size_t k = from; k < statuses.size(); ++k) {
        if (statuses[k].simulation_id != id) continue;
        ++seen;
        matching += statuses[k].run_state == run_state ? 1 : 0;
      }
      return seen >= 2;
    }, 5.0);
    return seen >= 2 && matching == seen;
  };
  auto next_two_are = [&](int64_t id, int run_state) {
    return two_from(statuses.size(), id, run_state);
  };

  // No --sim: attached to whichever sim it heard first, named in the reply.
  CmdResult r = cmd({"pause"});
  ASSERT_EQ(r.status, kCmdOk) << r.err;
  const bool first_paused = Contains(r.out, "simulation " + std::to_string(first_id) + " ");
  ASSERT_TRUE(first_paused || Contains(r.out, "simulation " + std::to_string(second_id) + " "))
      << r.out;
  const int64_t paused_id = first_paused ? first_id : second_id;
  const int64_t running_id = first_paused ? second_id : first_id;
  // The statuses after the paused one were sent after the pause came.
  size_t after_pause = 0;
  ASSERT_TRUE(bus.Until([&] {
    for (size_t k = 0; k < statuses.size(); ++k)
      if (statuses[k].simulation_id == paused_id && statuses[k].run_state == status_t::RUN_PAUSED)
        after_pause = k + 1;
    return after_pause > 0;
  }, 5.0));
  EXPECT_TRUE(two_from(after_pause, running_id, status_t::RUN_RUNNING))
      << "the other sim was paused too";
  EXPECT_TRUE(two_from(after_pause, paused_id, status_t::RUN_PAUSED));

  // --sim: that one quits, the other stays (paused) and still answers.
  SimProcess& quitting = first_paused ? second : first;
  SimProcess& staying = first_paused ? first : second;
  r = cmd({"--sim", std::to_string(running_id), "quit"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_EQ(quitting.Wait(std::chrono::seconds(10)), 0);
  EXPECT_TRUE(staying.running()) << staying.Log();
  EXPECT_TRUE(next_two_are(paused_id, status_t::RUN_PAUSED));

  // A simulation not on the bus: nothing sent, no answer, named.
  r = cmd({"--sim", "42", "--timeout", "1", "resume"});
  EXPECT_EQ(r.status, kCmdNoAnswer);
  EXPECT_TRUE(Contains(r.err, "no SIM_STATUS of simulation 42 within 1 s on " + url)) << r.err;
  EXPECT_TRUE(next_two_are(paused_id, status_t::RUN_PAUSED));

  r = cmd({"--sim", std::to_string(paused_id), "quit"});
  EXPECT_EQ(r.status, kCmdOk) << r.err;
  EXPECT_EQ(staying.Wait(std::chrono::seconds(10)), 0);
}

TEST_F(CmdTest, UsageErrorsAndNoSim) {
  const std::string url = BusUrl(12);
  CmdResult r = RunInProcess({"--help"});
  EXPECT_EQ(r.status, kCmdOk);
  EXPECT_TRUE(Contains(r.out, "Usage: simpartner-cmd [options] COMMAND [ARGS]")) << r.out;
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{},
                                             {"fly"},
                                             {"set"},
                                             {"set", "Axle1Motor"},
                                             {"--timeout", "x", "status"},
                                             {"--frobnicate", "status"},
                                             {"pause", "--follow"},
                                             {"model", "--body", "Torso"},
                                             {"status", "--out", "x.png"}}) {
    r = RunInProcess(args);
    EXPECT_EQ(r.status, kCmdUsage) << r.err;
    EXPECT_TRUE(Contains(r.err, "simpartner-cmd: ")) << r.err;
  }
  r = RunInProcess({"--lcm-url", url, "--timeout", "0.3", "set", "Axle1Motor", "300,1"});
  EXPECT_EQ(r.status, kCmdNoAnswer);
  EXPECT_TRUE(Contains(r.err, "no sim on " + url)) << r.err;
  r = RunInProcess({"--lcm-url", url, "--timeout", "0.3", "pause"});
  EXPECT_EQ(r.status, kCmdNoAnswer);
  r = RunInProcess({"--lcm-url", url, "--timeout", "0.3", "status"});
  EXPECT_EQ(r.status, kCmdNoAnswer);
  EXPECT_TRUE(Contains(r.err, "no SIM_STATUS within 0.3 s on " + url)) << r.err;

  // Without --lcm-url: the bus of the parameters file the other programs read.
  const std::string params = (dir_ / "params.txt").string();
  std::ofstream(params) << "lcmUrl=" << url << "\n";
  r = RunInProcess({"--params", params, "--timeout", "0.3", "status"});
  EXPECT_EQ(r.status, kCmdNoAnswer);
  EXPECT_TRUE(Contains(r.err, " on " + url)) << r.err;
  const std::string bad = (dir_ / "bad.txt").string();
  std::ofstream(bad) << "# comment\nlcmUrl=" << url << "\nstepsise=0.01\n";
  r = RunInProcess({"--params", bad, "status"});
  EXPECT_EQ(r.status, kCmdUsage);
  EXPECT_TRUE(Contains(r.err, bad + ":3")) << r.err;
}

// The shell commands of docs/driving.md, as a user types them: the real
// binary.
TEST_F(CmdTest, TheProgramFromAShell) {
  const std::string url = BusUrl(13);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, (dir_ / "sim.log").string(), {"--speed=0"});
  ASSERT_TRUE(sim.WaitUntilRunning(30)) << sim.Log();
  auto run = [&](std::vector<std::string> args, const std::string& log) {
    args.insert(args.begin(), {"--lcm-url", url});
    return RunToEnd(BuiltCommand("simpartner-cmd", args), (dir_ / log).string(), std::chrono::seconds(20))
        .status;
  };
  EXPECT_EQ(run({"set", "Axle1Motor", "300,1.0"}, "set.log"), kCmdOk);
  EXPECT_TRUE(Contains(ReadText((dir_ / "set.log").string()), "Axle1Motor: accepted"));
  EXPECT_EQ(run({"set", "Axle1Motor", "300,1e9"}, "refused.log"), kCmdRefused);
  EXPECT_TRUE(Contains(ReadText((dir_ / "refused.log").string()), "refused by the sim"));
  EXPECT_EQ(run({"set", "Wheel1", "300,1"}, "unknown.log"), kCmdUnknownName);
  EXPECT_EQ(run({"sett", "Axle1Motor", "300,1"}, "usage.log"), kCmdUsage);
  // The wheel turns: its joint rate in SIM_STATE.
  ClientOptions o;
  o.url = url;
  o.program = "cmd_test";
  Client client(o);
  const state_t now = *client.LatestState();
  const state_t s = client.WaitUntilSimTime(now.sim_time + 0.5, 10.0);
  EXPECT_NEAR(s.joints[static_cast<size_t>(client.catalog()->JointIndex("Axle1"))].rate[0], 1.0,
              0.1);
  EXPECT_EQ(run({"--timeout", "0.3", "--lcm-url", BusUrl(14), "status"}, "nosim.log"),
            kCmdNoAnswer);
}

}  // namespace
}  // namespace simpartner::client
