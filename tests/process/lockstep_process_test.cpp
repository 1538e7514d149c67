// Lock-step between real processes on real LCM multicast: a closed-loop
// controller (examples/drive_to_point, in C++) gives the same SIM_STATE
// stream, compared by hash, as fast as possible and at real time, on a
// machine loaded on every core, and from another network namespace; the
// same controller without lock-step gives different runs, so the
// comparison can fail. A controller that stalls or dies is released (the
// sim names it and runs on), and forged marks change nothing. The closed
// loop's repeating at any speed and under load runs once per physics
// engine (LockStepEngineTest); the rest is the sim's lock-step protocol,
// whatever steps it, and runs with the default engine.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/client/client.h"
#include "simpartner/client/lock_step.h"
#include "simpartner/child_process.h"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/sync_reply_t.hpp"
#include "simpartner/sync_t.hpp"
#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/encode.h"
#include "../support/engines.h"
#include "../support/netns.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"

namespace simpartner {
namespace {

using test_support::BuiltCommand;
using test_support::BusUrl;
using test_support::ReadText;
using test_support::SimCommand;

// The goal drive_to_point steers gen1 to: about 4.6 s of sim time.
const std::vector<std::string> kGoal = {"3", "-1"};

// Everything the sim publishes that a comparison of runs needs: the states
// by step (wall clock and simulation id zeroed: they differ run to run),
// the sync replies, the newest status.
class RunListener : public test_support::BusListener {
 public:
  explicit RunListener(const std::string& url) : BusListener(url) {
    Subscribe<state_t>(channels::kState, [this](const state_t& s) {
      state_t copy = s;
      copy.utime = 0;
      copy.simulation_id = 0;
      states[s.step] = test_support::Encode(copy);
    });
    Keep(channels::kSyncReply, &sync_replies);
    KeepLatest(channels::kStatus, &status);
  }

  // FNV-1a over the states of steps 1..last in order; 0 when one is missing
  // (a lost datagram would make runs differ for the listener's sake).
  uint64_t Hash(int64_t last) const {
    uint64_t h = 1469598103934665603ull;
    for (int64_t step = 1; step <= last; ++step) {
      const auto it = states.find(step);
      if (it == states.end()) return 0;
      for (uint8_t byte : it->second) h = (h ^ byte) * 1099511628211ull;
    }
    return h;
  }
  // The sim has said how it is, so it listens: a controller started before
  // waits only 3 s for the model, and a sanitized sim on a loaded machine
  // took longer than that to start.
  bool UntilSimUp() {
    return Until([&] { return status.utime != 0; }, 30);
  }
  bool Released(const std::string& controller) const {
    for (const sync_reply_t& r : sync_replies)
      if (r.controller == controller && r.event == sync_reply_t::EVENT_RELEASED) return true;
    return false;
  }

  std::map<int64_t, std::vector<uint8_t>> states;
  std::vector<sync_reply_t> sync_replies;
  status_t status{};
};

struct RunResult {
  int status = -1;
  std::string output;
  int64_t last_tick = -1;  // the controller's last tick, from its output
  uint64_t hash = 0;
};

int64_t LastTick(const std::string& output) {
  const size_t at = output.find("tick ");
  return at == std::string::npos ? -1 : std::stoll(output.substr(at + 5));
}

// A controller's output without the client's warning that the bus is open
// to other machines (bus_exposure.h): it names the bus, which differs from
// run to run; the rest must be the same.
std::string WithoutBusWarning(const std::string& output) {
  std::istringstream lines(output);
  std::string kept;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("simpartner client: warning: the bus ", 0) != 0) kept += line + "\n";
  return kept;
}

class LockStepProcessTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_lockstep_", 40); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // gen1 on flat ground, paused, at `speed`, on engine_; drive_to_point with `period`
  // (0: without lock-step). `controller_host` runs the controller in a
  // network namespace (with the sim in `sim_host`) when a LAN is given.
  // A lock-step run is paced to the test's listener (Pace); one without
  // is not (a pacer would put it in lock-step).
  RunResult ClosedLoop(double speed, int period, const std::string& name,
                       const test_support::NamespaceLan* lan = nullptr) {
    std::string url = BusUrl(next_bus_++);
    if (lan) url.replace(url.find("ttl=0"), 5, "ttl=1");
    std::vector<std::string> sim_argv =
        SimCommand(test_support::ShippedWorld("gen1_flat.xml"), url,
                   {"--startPaused=1", "--speed=" + std::to_string(speed),
                    test_support::EngineFlag(engine_)});
    if (lan) sim_argv = lan->Exec("sim", sim_argv);
    // The listener and the pacer hear the sim on its own host.
    auto on_sim_host = [&] {
      return lan ? std::make_unique<test_support::ScopedNetns>(lan->Namespace("sim")) : nullptr;
    };
    std::unique_ptr<test_support::ScopedNetns> inside = on_sim_host();
    RunListener listener(url);
    inside.reset();
    ChildProcess sim(sim_argv, (dir_ / (name + "_sim.log")).string());
    if (!listener.UntilSimUp()) ADD_FAILURE() << "no SIM_STATUS within 30 s from the sim of " << name;
    std::unique_ptr<client::Client> pacer;
    if (period > 0) {
      inside = on_sim_host();
      client::ClientOptions options;
      options.url = url;
      options.program = "pacer";
      options.model_timeout = 30;
      pacer = std::make_unique<client::Client>(options);
      inside.reset();
    }
    std::vector<std::string> controller = BuiltCommand(
        "drive_to_point",
        {"--lcm-url", url, "--x", kGoal[0], "--z", kGoal[1], "--period", std::to_string(period)});
    if (lan) controller = lan->Exec("ctl", controller);
    const std::string log = (dir_ / (name + "_controller.log")).string();
    RunResult run;
    if (pacer) {
      ChildProcess running(controller, log);
      Pace(*pacer, listener, running);
      run.status = running.Wait(std::chrono::seconds(120)).value_or(-1);
    } else {
      run.status = test_support::RunToEnd(controller, log, std::chrono::seconds(120)).status;
    }
    const std::string output = ReadText(log);
    run.output = WithoutBusWarning(output);
    run.last_tick = LastTick(output);
    // The states up to the last tick were published before it was answered.
    listener.Until([&] { return listener.states.count(run.last_tick) > 0; }, 5);
    run.hash = listener.Hash(run.last_tick);
    sim.Signal(SIGTERM);
    sim.Wait(std::chrono::seconds(10));
    return run;
  }

  // Paces the paused sim to `listener` until `controller` has ended: a
  // lock-step controller of the test's own, a tick every kPacerPeriod
  // steps, answered with no command once the listener has read the tick's
  // state. At speed 0 an unpaced sim outran a listener starved of CPU by
  // more than its 4 MB socket buffer while the test waited for the
  // controller: states lost, a hash of 0. A silent controller does not
  // change the run (TwoControllersAtDifferentPeriods).
  static constexpr int kPacerPeriod = 50;
  void Pace(client::Client& pacer, RunListener& listener, ChildProcess& controller) {
    client::LockStepOptions every;
    every.period = kPacerPeriod;
    every.resume = false;  // the controller resumes when it has joined
    every.timeout = 30;
    try {
      client::LockStep loop(pacer, every);
      loop.Next();  // the paused sim's own step, where it waits for the controller
      while (controller.running()) {
        const int64_t step = loop.Next().step;
        if (!listener.Until([&] { return listener.states.count(step) > 0; }, 30)) {
          ADD_FAILURE() << "the listener did not read the state of step " << step;
          return;
        }
      }
    } catch (const client::LockStepError& e) {
      ADD_FAILURE() << e.what();
    }
  }

  std::filesystem::path dir_;
  int next_bus_ = 0;
  std::string engine_ = "ode";  // of ClosedLoop's sim
};

// The closed loop on each engine: lock-step and publishing are shared, but
// the states that must repeat bit for bit are the engine's.
class LockStepEngineTest : public LockStepProcessTest,
                           public ::testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    LockStepProcessTest::SetUp();
    engine_ = GetParam();
  }
};
INSTANTIATE_TEST_SUITE_P(Engines, LockStepEngineTest, test_support::AllEngines(),
                         test_support::EngineTestName);

// drive_to_point gives up at 60 s of sim time (60000 ticks of 1 ms steps);
// before that, the closed loop brought the robot within 0.2 m of the goal.
constexpr int64_t kGivesUpAtTick = 60000;

TEST_P(LockStepEngineTest, AClosedLoopRepeatsBitForBitAtAnySpeed) {
  const RunResult fast = ClosedLoop(0, 10, "fast");
  ASSERT_EQ(fast.status, 0) << fast.output;
  ASSERT_GT(fast.last_tick, 4000) << fast.output;
  ASSERT_LT(fast.last_tick, kGivesUpAtTick) << "the goal was not reached\n" << fast.output;
  ASSERT_NE(fast.hash, 0u) << "a state went missing for the listener";
  const RunResult again = ClosedLoop(0, 10, "again");
  const RunResult real_time = ClosedLoop(1, 10, "real_time");
  EXPECT_EQ(again.output, fast.output);
  EXPECT_EQ(real_time.output, fast.output);
  EXPECT_EQ(again.hash, fast.hash);
  EXPECT_EQ(real_time.hash, fast.hash);
}

TEST_P(LockStepEngineTest, AClosedLoopRepeatsOnAMachineLoadedOnEveryCore) {
  const RunResult quiet = ClosedLoop(0, 1, "quiet");
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  ASSERT_LT(quiet.last_tick, kGivesUpAtTick) << "the goal was not reached\n" << quiet.output;
  std::vector<std::unique_ptr<ChildProcess>> busy;
  for (long core = 0; core < ::sysconf(_SC_NPROCESSORS_ONLN); ++core)
    busy.push_back(std::make_unique<ChildProcess>(
        std::vector<std::string>{"/bin/sh", "-c", "while :; do :; done"}, "/dev/null"));
  const RunResult loaded = ClosedLoop(0, 1, "loaded");
  busy.clear();
  EXPECT_EQ(loaded.output, quiet.output);
  EXPECT_EQ(loaded.hash, quiet.hash);
  EXPECT_NE(quiet.hash, 0u);
}

TEST_F(LockStepProcessTest, AClosedLoopRepeatsWithTheControllerOnAnotherHost) {
  ASSERT_EQ(::geteuid(), 0u) << "network namespaces need root";
  const RunResult here = ClosedLoop(0, 10, "here");
  ASSERT_EQ(here.status, 0) << here.output;
  test_support::NamespaceLan lan("spls", {"sim", "ctl"});
  const RunResult there = ClosedLoop(0, 10, "there", &lan);
  EXPECT_EQ(there.status, 0) << there.output;
  EXPECT_EQ(there.output, here.output);
  EXPECT_EQ(there.hash, here.hash);
  EXPECT_NE(here.hash, 0u);
}

// Two synchronous controllers at different periods: drive_to_point every
// 10 steps and an observer of the test's own every 7 that answers with no
// command. The sim waits for each at its ticks (both at step 70, 140 ...),
// and the run is the very run drive_to_point gives alone.
TEST_F(LockStepProcessTest, TwoControllersAtDifferentPeriods) {
  const RunResult alone = ClosedLoop(0, 10, "alone");
  ASSERT_EQ(alone.status, 0) << alone.output;

  const std::string url = BusUrl(next_bus_++);
  RunListener listener(url);
  ChildProcess sim(SimCommand(test_support::ShippedWorld("gen1_flat.xml"), url,
                              {"--startPaused=1", "--speed=0"}),
                   (dir_ / "two_sim.log").string());
  ASSERT_TRUE(listener.UntilSimUp());
  client::ClientOptions options;
  options.url = url;
  options.program = "observer";
  options.model_timeout = 10;
  client::Client observer(options);
  client::LockStepOptions every7;
  every7.period = 7;
  every7.resume = false;  // drive_to_point resumes when it has joined too
  client::LockStep loop(observer, every7);
  ChildProcess controller(
      BuiltCommand("drive_to_point",
                   {"--lcm-url", url, "--x", kGoal[0], "--z", kGoal[1], "--period", "10"}),
      (dir_ / "two_controller.log").string());
  int64_t ticks = 0;
  try {
    for (;; ++ticks) {
      const state_t& s = loop.Next();
      ASSERT_EQ(s.step % 7, 0);
      // Answered once the listener has the tick's state: the observer
      // paces the sim as Pace does.
      ASSERT_TRUE(listener.Until([&] { return listener.states.count(s.step) > 0 || s.step == 0; }, 30))
          << "the listener did not read the state of step " << s.step;
      if (!controller.running() && s.step > alone.last_tick) break;
    }
  } catch (const client::LockStepError& e) {
    FAIL() << e.what();
  }
  ASSERT_TRUE(controller.Wait(std::chrono::seconds(10)).has_value());
  const std::string output = WithoutBusWarning(ReadText(dir_ / "two_controller.log"));
  EXPECT_EQ(output, alone.output);
  listener.Until([&] { return listener.states.count(alone.last_tick) > 0; }, 5);
  EXPECT_EQ(listener.Hash(alone.last_tick), alone.hash);
  EXPECT_GT(ticks, alone.last_tick / 7 - 2);  // every tick of the observer's came
  // Both ticks' states were published: multiples of 7 and of 10.
  EXPECT_TRUE(listener.states.count(70) && listener.states.count(77) && listener.states.count(80));
}

// The comparison above can fail: the same controller reading the newest
// state and sending as it goes (period 0) lands its commands wherever the
// machine puts them.
TEST_F(LockStepProcessTest, WithoutLockStepTheSameControllerGivesDifferentRuns) {
  const RunResult fast = ClosedLoop(0, 0, "async_fast");
  const RunResult real_time = ClosedLoop(1, 0, "async_real_time");
  ASSERT_EQ(fast.status, 0) << fast.output;
  ASSERT_EQ(real_time.status, 0) << real_time.output;
  const int64_t last = std::min(fast.last_tick, real_time.last_tick);
  ASSERT_GT(last, 4000);
  EXPECT_NE(fast.hash == real_time.hash && fast.output == real_time.output, true)
      << "two runs without lock-step came out the same";
}

TEST_F(LockStepProcessTest, AStalledControllerIsReleasedAndTheRunGoesOn) {
  const std::string url = BusUrl(90);
  RunListener listener(url);
  ChildProcess sim(SimCommand(test_support::ShippedWorld("gen1_flat.xml"), url,
                              {"--startPaused=1", "--speed=1", "--lockStepTimeout=1"}),
                   (dir_ / "sim.log").string());
  ASSERT_TRUE(listener.UntilSimUp());
  const std::string log = (dir_ / "controller.log").string();
  ChildProcess controller(BuiltCommand("drive_to_point", {"--lcm-url", url, "--x", "50", "--z", "0", "--period", "10"}), log);
  ASSERT_TRUE(listener.Until([&] { return listener.states.size() > 500; }, 10));
  controller.Signal(SIGSTOP);
  const auto stopped_at = std::chrono::steady_clock::now();
  ASSERT_TRUE(listener.Until([&] { return listener.Released("drive_to_point"); }, 5))
      << ReadText(dir_ / "sim.log");
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stopped_at).count();
  EXPECT_GE(waited, 0.9);
  EXPECT_LT(waited, 3.0);
  // Said on stderr with the controller's name and the tick, and in SIM_STATUS.
  const std::string sim_log = ReadText(dir_ / "sim.log");
  EXPECT_NE(sim_log.find("lockstep: released controller 'drive_to_point'"), std::string::npos)
      << sim_log;
  EXPECT_NE(sim_log.find("within 1 s (lockStepTimeout); from this tick on it is not synchronous"),
            std::string::npos)
      << sim_log;
  // The run goes on without it.
  const int64_t step = listener.states.rbegin()->first;
  EXPECT_TRUE(listener.Until([&] { return listener.states.rbegin()->first > step + 500; }, 5));
  listener.Until([&] { return listener.status.num_warnings > 0; }, 3);
  bool named = false;
  for (const warning_t& w : listener.status.warnings)
    named = named || (w.source == "lockstep" && w.message.find("drive_to_point") != std::string::npos);
  EXPECT_TRUE(named);
  // Woken, the controller learns it and ends saying so.
  controller.Signal(SIGCONT);
  const auto status = controller.Wait(std::chrono::seconds(20));
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(*status, 1);
  EXPECT_NE(ReadText(log).find("released by the sim at tick"), std::string::npos) << ReadText(log);
}

TEST_F(LockStepProcessTest, AControllerThatDiesIsReleased) {
  const std::string url = BusUrl(91);
  RunListener listener(url);
  ChildProcess sim(SimCommand(test_support::ShippedWorld("gen1_flat.xml"), url,
                              {"--startPaused=1", "--speed=0", "--lockStepTimeout=0.5"}),
                   (dir_ / "sim.log").string());
  ASSERT_TRUE(listener.UntilSimUp());
  ChildProcess controller(BuiltCommand("drive_to_point", {"--lcm-url", url, "--x", "50", "--z", "0", "--period", "1"}),
                          (dir_ / "controller.log").string());
  ASSERT_TRUE(listener.Until([&] { return listener.states.size() > 200; }, 10));
  controller.Signal(SIGKILL);
  EXPECT_TRUE(listener.Until([&] { return listener.Released("drive_to_point"); }, 5));
  const int64_t step = listener.states.rbegin()->first;
  EXPECT_TRUE(listener.Until([&] { return listener.states.rbegin()->first > step + 1000; }, 5));
}

// Marks for ticks that never happened, another process's marks for the
// controller's name and replays of old ones: refused and counted, and the
// run is the very run it is without them. On an unsigned bus, where only
// the marks' tokens tell the controller from a forger.
TEST_F(LockStepProcessTest, ForgedAndDuplicatedMarksChangeNothing) {
  const test_support::UnsignedBus unsigned_bus;
  const RunResult clean = ClosedLoop(0, 10, "clean");
  ASSERT_EQ(clean.status, 0) << clean.output;

  const std::string url = BusUrl(92);
  RunListener listener(url);
  ChildProcess sim(SimCommand(test_support::ShippedWorld("gen1_flat.xml"), url,
                              {"--startPaused=1", "--speed=0"}),
                   (dir_ / "forged_sim.log").string());
  ASSERT_TRUE(listener.UntilSimUp());
  ChildProcess controller(
      BuiltCommand("drive_to_point",
                   {"--lcm-url", url, "--x", kGoal[0], "--z", kGoal[1], "--period", "10"}),
      (dir_ / "forged_controller.log").string());
  int forged = 0, forged_as_it = 0;
  auto forge = [&](const std::string& name, const std::string& sender, int64_t tick,
                   int8_t action = sync_t::ACTION_DONE) {
    sync_t m{};
    m.controller = name;
    m.sender = sender;
    m.action = action;
    m.tick = tick;
    listener.lcm().publish(channels::kSync, &m);
    ++forged;
  };
  while (controller.running() && forged < 300) {
    listener.Pump(0.005);
    const int64_t step = listener.states.empty() ? 0 : listener.states.rbegin()->first;
    forge("drive_to_point", "forger@elsewhere:1", step - step % 10);  // not its sender
    forge("drive_to_point", "forger@elsewhere:1", step + 1000000);    // never happened
    forge("ghost", "ghost@nowhere:2", step);                          // never joined
    // The audit's: its own name and sender, as SIM_STATUS lists them, a
    // DONE for the tick the sim waits at and a LEAVE (which once made the
    // controller fail, "it has not joined"), without its token.
    if (listener.status.sync_controllers.empty() || forged_as_it >= 20) continue;
    const std::string its_sender = listener.status.sync_controllers[0].sender;
    forge("drive_to_point", its_sender, step - step % 10);
    forge("drive_to_point", its_sender, 0, sync_t::ACTION_LEAVE);
    forged_as_it += 2;
  }
  ASSERT_TRUE(controller.Wait(std::chrono::seconds(60)).has_value());
  const std::string output = WithoutBusWarning(ReadText(dir_ / "forged_controller.log"));
  const int64_t last = LastTick(output);
  listener.Until([&] { return listener.states.count(last) > 0; }, 5);
  EXPECT_EQ(output, clean.output);
  EXPECT_EQ(listener.Hash(last), clean.hash);
  ASSERT_GT(forged, 30);
  // Every one counted as a bad message by the sim, none fatal.
  listener.Until([&] { return listener.status.bad_messages >= forged; }, 3);
  EXPECT_GE(listener.status.bad_messages, forged);
  int refused = 0, refused_as_it = 0;
  for (const sync_reply_t& r : listener.sync_replies) {
    if (r.event != sync_reply_t::EVENT_REFUSED) continue;
    refused += r.sender == "forger@elsewhere:1" || r.sender == "ghost@nowhere:2";
    refused_as_it += r.reason.find("without the token its JOINED gave") != std::string::npos;
  }
  EXPECT_GE(refused, forged - forged_as_it);
  EXPECT_GT(forged_as_it, 0);
  EXPECT_EQ(refused_as_it, forged_as_it);
}

}  // namespace
}  // namespace simpartner
