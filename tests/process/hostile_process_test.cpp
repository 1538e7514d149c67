// The hostile corpus (tests/support/hostile_corpus.h: every channel, every
// message type) sent on real LCM multicast to a running simpartner-sim,
// simpartner-logger (real private MariaDB), simpartner-viewer and
// simpartner-camera (own Xvfb) at once. After each message every process must still run; after
// all of them the sim still steps and takes a good command, the viewer
// still draws the sim's newest state, and the logger has every step with
// all of its rows. The sim's part runs again on its own with the MuJoCo
// engine (HostileSimTest): the logger and the viewer do not know which
// engine runs, so they meet the corpus once.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <fstream>

#include "../logger/logger_test_support.h"
#include "../sim_core/test_worlds.h"
#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/engines.h"
#include "../support/hostile_corpus.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "../support/wait.h"
#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/viewer/xvfb.h"

namespace simpartner {
namespace {

using test_support::BuiltCommand;
using test_support::ReadText;

// The test's side of the bus: newest step, the sim's newest status and the
// replies to this test's commands. Only what comes from the sim itself
// counts (the corpus also sends forged states and statuses, which the test
// must not believe).
class Observer : public test_support::BusListener {
 public:
  explicit Observer(const std::string& url) : BusListener(url) {
    Subscribe<state_t>(channels::kState, [this](const state_t& s) {
      if (simulation_id < 0) simulation_id = s.simulation_id;
      if (s.simulation_id == simulation_id && s.num_bodies > 1 && s.step < 10000000)
        last_step = std::max(last_step, s.step);
    });
    Subscribe<status_t>(channels::kStatus, [this](const status_t& s) {
      if (s.simulation_id != simulation_id || s.host == "elsewhere") return;
      status = s;
      has_status = true;
    });
    Subscribe<command_reply_t>(channels::kCommandReply, [this](const command_reply_t& r) {
      if (r.sender == "hostile-test") replies.push_back(r);
    });
  }

  int64_t simulation_id = -1;
  int64_t last_step = -1;
  status_t status{};
  bool has_status = false;
  std::vector<command_reply_t> replies;
};

// A process the corpus must not kill, and where it writes.
struct Process {
  const char* name;
  ChildProcess* child;
  std::filesystem::path log;
};

// Every corpus message three times on the bus, checking after each that
// all of `processes` still run. *undecodable_for_sim: how many of the
// datagrams the sim cannot decode on its channels (it counts them).
void SendCorpus(Observer& bus, const std::vector<Process>& processes, int* undecodable_for_sim) {
  *undecodable_for_sim = 0;
  for (const test_support::HostileMessage& m : test_support::HostileCorpus(bus.simulation_id)) {
    std::cout << "sending: " << m.name << " on " << m.channel << " (" << m.bytes.size() << " bytes)\n";
    for (int repeat = 0; repeat < 3; ++repeat) {
      bus.PublishBytes(m.channel, m.bytes.data(), static_cast<unsigned>(m.bytes.size()));
      bus.Pump(0.01);
    }
    if (m.undecodable && (m.channel == channels::kCommand || m.channel == channels::kControl ||
                          m.channel == channels::kModelRequest))
      *undecodable_for_sim += 3;
    bus.Pump(0.03);
    for (const Process& p : processes)
      ASSERT_TRUE(p.child->running()) << p.name << " died after '" << m.name << "' on " << m.channel
                                      << ":\n" << ReadText(p.log);
  }
}

// The sim after the corpus: still stepping (500 steps, half a second at
// its pace; 10 s allowed, as a loaded machine runs it slower), counted
// the refusals, said why for one, takes a good command.
void ExpectSimStillWorks(Observer& bus, int undecodable_for_sim, const std::filesystem::path& log) {
  const int64_t step_after_corpus = bus.last_step;
  EXPECT_TRUE(bus.Until([&] { return bus.last_step > step_after_corpus + 500; }, 10))
      << "the sim stopped stepping at " << bus.last_step;
  ASSERT_TRUE(bus.Until([&] { return bus.has_status && bus.status.bad_messages >= undecodable_for_sim; }, 5))
      << "bad_messages " << bus.status.bad_messages << " of " << undecodable_for_sim << "\n"
      << ReadText(log);
  EXPECT_EQ(bus.status.run_state, status_t::RUN_RUNNING);
  EXPECT_GE(bus.status.target_speed, 1.0);  // the nonsense speeds were refused
  command_t good{};
  good.sender = "hostile-test";
  good.request_id = 1;
  good.target = "ArmMotor";
  good.action = command_t::ACTION_SET;
  good.apply_at_step = -1;
  good.values = {1000, 1000, 1000, 0, 0, 0.5, 20, 0, 0};  // angle 0.5 rad, P = 20
  good.num_values = 9;
  bus.Publish(channels::kCommand, good);
  ASSERT_TRUE(bus.Until([&] { return !bus.replies.empty(); }, 5));
  EXPECT_TRUE(bus.replies.back().accepted) << bus.replies.back().reason;
  const std::string sim_log = ReadText(log);
  EXPECT_NE(sim_log.find("SIM_COMMAND: 48 bytes refused as simpartner.command_t: field 'sender' at "
                         "byte 32: string length 0"),
            std::string::npos)
      << sim_log;
}

class HostileProcessTest : public logger::testing::ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    url_ = test_support::BusUrl(0);
    world_ = sim::testing::WriteArmWorld(dir_);
  }
  // Each process in a session of its own (ChildOptions::own_session), as
  // scripts/run starts them.
  // With a busy loop on each core in the runner's group, a viewer there
  // heard none of the corpus once.
  std::unique_ptr<ChildProcess> Start(const std::vector<std::string>& argv, const std::string& log) {
    ChildOptions options;
    options.own_session = true;
    return std::make_unique<ChildProcess>(argv, (dir_ / log).string(), options);
  }

  // Quits the sim and returns the last step it says it made (-1 when it
  // did not say): the sim's own word, as this test's listener can be
  // behind on a loaded machine.
  int64_t QuitSim(Observer& bus, ChildProcess* sim) {
    control_t quit{};
    quit.sender = "hostile-test";
    quit.action = control_t::ACTION_QUIT;
    bus.Publish(channels::kControl, quit);
    EXPECT_EQ(sim->Wait(std::chrono::seconds(10)).value_or(-1), 0) << ReadText(dir_ / "sim.log");
    const std::string sim_log = ReadText(dir_ / "sim.log");
    const std::string ended_line = "simpartner-sim: ended at step ";
    const size_t ended = sim_log.find(ended_line);
    if (ended == std::string::npos) {
      ADD_FAILURE() << "the sim did not say its last step:\n" << sim_log;
      return -1;
    }
    return std::atoll(sim_log.c_str() + ended + ended_line.size());
  }

  std::string url_;
  std::string world_;  // the arm world
};

TEST_F(HostileProcessTest, EveryProcessSurvivesTheCorpusAndKeepsWorking) {
  Observer bus(url_);
  auto logger = Start(BuiltCommand("simpartner-logger",
                                   {"--params", "/dev/null", "--lcm-url", url_, "--db-options",
                                    server_->logger_options(), "--spool", (dir_ / "spool").string(),
                                    "--status-period", "1"}),
                      "logger.log");
  ASSERT_TRUE(bus.UntilFileHolds(dir_ / "logger.log", ": logging udpm://", 30)) << ReadText(dir_ / "logger.log");
  auto sim = Start(test_support::SimCommand(world_, url_, {"--statusPeriod=0.2"}), "sim.log");
  ASSERT_TRUE(bus.Until([&] { return bus.last_step > 100; }, 20)) << ReadText(dir_ / "sim.log");

  viewer::XvfbServer xvfb(640, 360, (dir_ / "xvfb.log").string());
  // The viewer's screenshot is taken with its key (p) once the corpus is
  // sent, not at a time set before: under load the corpus took longer
  // than the 12 s a timed screenshot waited, and the viewer ended in the
  // middle of it. It writes viewer-<time>.png where it runs: in the test's
  // directory.
  auto viewer = Start(test_support::OnDisplay(
                          xvfb.display(),
                          test_support::InDirectory(
                              dir_.string(), BuiltCommand("simpartner-viewer",
                                                          {"--params", "/dev/null", "--lcm-url", url_,
                                                           "--width", "640", "--height", "360"}))),
                      "viewer.log");
  // simpartner-camera on the same display meets the corpus too (the arm
  // has no camera: it follows the bus and refuses what does not fit).
  auto camera = Start(test_support::OnDisplay(xvfb.display(),
                                              BuiltCommand("simpartner-camera",
                                                           {"--params", "/dev/null", "--lcm-url", url_})),
                      "camera.log");
  bus.Pump(2.0);  // the viewer and the camera learn the model

  int undecodable_for_sim = 0;
  ASSERT_NO_FATAL_FAILURE(SendCorpus(bus,
                                     {{"simpartner-sim", sim.get(), dir_ / "sim.log"},
                                      {"simpartner-logger", logger.get(), dir_ / "logger.log"},
                                      {"simpartner-viewer", viewer.get(), dir_ / "viewer.log"},
                                      {"simpartner-camera", camera.get(), dir_ / "camera.log"}},
                                     &undecodable_for_sim));
  const int64_t step_after_corpus = bus.last_step;
  ASSERT_NO_FATAL_FAILURE(ExpectSimStillWorks(bus, undecodable_for_sim, dir_ / "sim.log"));

  // The viewer: its screenshot, taken after the corpus, shows a state the
  // sim published after the corpus. No window manager: the keyboard's
  // focus follows the pointer onto the viewer's window, which fills the
  // screen.
  for (const std::vector<std::string>& keys :
       {std::vector<std::string>{"mousemove", "320", "180"}, std::vector<std::string>{"key", "p"}}) {
    const test_support::ProgramRun run =
        test_support::RunXdotool(xvfb.display(), keys, (dir_ / "xdotool.log").string());
    ASSERT_EQ(run.status, 0) << run.output;
  }
  ASSERT_TRUE(bus.UntilFileHolds(dir_ / "viewer.log", "simpartner-viewer: screenshot", 30))
      << ReadText(dir_ / "viewer.log");
  viewer->Signal(SIGTERM);
  // Its exit (GL teardown, the sanitizers' leak check) took over 10 s once
  // with the whole system of another test beside it on 2 cores.
  ASSERT_EQ(viewer->Wait(std::chrono::seconds(60)).value_or(-1), 0) << ReadText(dir_ / "viewer.log");
  const std::string viewer_log = ReadText(dir_ / "viewer.log");
  const size_t at = viewer_log.find(", step ", viewer_log.find("simpartner-viewer: screenshot"));
  ASSERT_NE(at, std::string::npos) << viewer_log;
  EXPECT_GT(std::atoll(viewer_log.c_str() + at + 7), step_after_corpus) << viewer_log;
  EXPECT_NE(viewer_log.find("refused as simpartner.state_t"), std::string::npos) << viewer_log;
  camera->Signal(SIGTERM);
  ASSERT_EQ(camera->Wait(std::chrono::seconds(30)).value_or(-1), 0) << ReadText(dir_ / "camera.log");
  const std::string camera_log = ReadText(dir_ / "camera.log");
  EXPECT_NE(camera_log.find("refused as simpartner.state_t"), std::string::npos) << camera_log;
  EXPECT_NE(camera_log.find(": 0 cameras\n"), std::string::npos)
      << camera_log;

  // The logger: the sim quits; every step it made is in the database once,
  // with a row for each of its 3 bodies and 2 joints, and nothing forged.
  const int64_t last = QuitSim(bus, sim.get());
  ASSERT_GT(last, 0);
  int64_t rows = -1;
  test_support::WaitFor(
      [&] {
        rows = QueryInt("SELECT COUNT(*) FROM SimulationRow WHERE simulationID = 1");
        return rows >= last;
      },
      60, std::chrono::milliseconds(300));
  EXPECT_EQ(rows, last) << ReadText(dir_ / "logger.log");
  EXPECT_EQ(QueryInt("SELECT MAX(step) FROM SimulationRow WHERE simulationID = 1"), last);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Simulation"), 1) << "a forged model became a simulation";
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Pose p JOIN SimulationRow r USING (simulationRowID) "
                     "WHERE r.simulationID = 1"),
            3 * last);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM JointPose j JOIN SimulationRow r USING (simulationRowID) "
                     "WHERE r.simulationID = 1"),
            2 * last);
  logger->Signal(SIGTERM);
  EXPECT_EQ(logger->Wait(std::chrono::seconds(60)).value_or(-1), 0) << ReadText(dir_ / "logger.log");
  EXPECT_NE(ReadText(dir_ / "logger.log").find("refused as simpartner.state_t"), std::string::npos)
      << ReadText(dir_ / "logger.log");
}

// The audit's copied model, on an unsigned bus (SIMPARTNER_BUS_KEY=none,
// where no key refuses it first): while a sequence plays, with the logger
// and the viewer following, a process sends 20 copies of the real
// SIM_MODEL, sender included, with another simulation id. The real
// simulation never stops publishing, so each follower takes the copy for
// another simulation: the sequence plays on, the viewer stays on the real
// model, and the logger logs the real simulation to its last step in its
// one Simulation row. (Before, the sequencer exited, the logger closed the
// real row mid-run and opened a phantom one, and the viewer switched.)
// Beside other tests, unlike the corpus: it sends no flood.
class CopiedModelTest : public HostileProcessTest {};

constexpr const char* kArmSequence = R"(<sequence version="2">
  <set target="ArmMotor">1000,1000,1000,0,0,0.5,20,0,0</set>
  <pause seconds="60"/>
  <set target="ArmMotor">1000,1000,1000,0,0,0,20,0,0</set>
</sequence>
)";

TEST_F(CopiedModelTest, OnAnUnsignedBusACopiedModelChangesNoFollower) {
  const test_support::UnsignedBus unsigned_bus;
  Observer bus(url_);
  model_t model{};
  bus.KeepLatest<model_t>(channels::kModel, &model);
  auto logger = Start(BuiltCommand("simpartner-logger",
                                   {"--params", "/dev/null", "--lcm-url", url_, "--db-options",
                                    server_->logger_options(), "--spool", (dir_ / "spool").string(),
                                    "--status-period", "1"}),
                      "logger.log");
  ASSERT_TRUE(bus.UntilFileHolds(dir_ / "logger.log", ": logging udpm://", 30))
      << ReadText(dir_ / "logger.log");
  auto sim = Start(test_support::SimCommand(world_, url_, {}), "sim.log");
  ASSERT_TRUE(bus.Until([&] { return bus.last_step > 100 && model.simulation_id != 0; }, 30))
      << ReadText(dir_ / "sim.log");
  const int64_t real = model.simulation_id;
  viewer::XvfbServer xvfb(640, 360, (dir_ / "xvfb.log").string());
  auto viewer = Start(test_support::OnDisplay(
                          xvfb.display(), BuiltCommand("simpartner-viewer",
                                                       {"--params", "/dev/null", "--lcm-url", url_,
                                                        "--width", "640", "--height", "360"})),
                      "viewer.log");
  ASSERT_TRUE(bus.UntilFileHolds(dir_ / "viewer.log", "model of simulation " + std::to_string(real), 30))
      << ReadText(dir_ / "viewer.log");
  std::ofstream(dir_ / "arm.xml") << kArmSequence;
  auto sequencer = Start(BuiltCommand("simpartner-sequencer",
                                      {(dir_ / "arm.xml").string(), "--lcm-url", url_}),
                         "sequencer.log");
  ASSERT_TRUE(bus.UntilFileHolds(dir_ / "sequencer.log", "line 2: set ArmMotor", 30))
      << ReadText(dir_ / "sequencer.log");

  model_t copy = model;
  copy.simulation_id = real + 1000;
  for (int i = 0; i < 20; ++i) {
    bus.lcm().publish(channels::kModel, &copy);  // unsigned, as a forger sends it
    bus.Pump(0.05);
  }
  const int64_t after_copies = bus.last_step;
  ASSERT_TRUE(bus.Until([&] { return bus.last_step > after_copies + 2000; }, 30));

  EXPECT_TRUE(sequencer->running()) << ReadText(dir_ / "sequencer.log");
  EXPECT_EQ(ReadText(dir_ / "sequencer.log").find("restarted"), std::string::npos)
      << ReadText(dir_ / "sequencer.log");
  EXPECT_EQ(ReadText(dir_ / "viewer.log").find("model of simulation " + std::to_string(copy.simulation_id)),
            std::string::npos)
      << ReadText(dir_ / "viewer.log");
  EXPECT_EQ(ReadText(dir_ / "logger.log").find("a new simulation started"), std::string::npos)
      << ReadText(dir_ / "logger.log");
  ASSERT_TRUE(viewer->running()) << ReadText(dir_ / "viewer.log");
  ASSERT_TRUE(logger->running()) << ReadText(dir_ / "logger.log");

  sequencer->Signal(SIGTERM);
  EXPECT_EQ(sequencer->Wait(std::chrono::seconds(30)).value_or(-1), 1) << ReadText(dir_ / "sequencer.log");
  const int64_t last = QuitSim(bus, sim.get());
  ASSERT_GT(last, 0);
  EXPECT_TRUE(test_support::WaitFor(
      [&] {
        return QueryInt("SELECT COUNT(*) FROM SimulationRow WHERE simulationID = 1") >= last &&
               QueryInt("SELECT COUNT(*) FROM Simulation WHERE simulationID = 1 AND lastStep IS "
                        "NOT NULL") == 1;
      },
      60, std::chrono::milliseconds(300)))
      << ReadText(dir_ / "logger.log");
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM Simulation"), 1)
      << "the copy became a simulation:\n" << ReadText(dir_ / "logger.log");
  EXPECT_EQ(QueryInt("SELECT lastStep FROM Simulation WHERE simulationID = 1"), last);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM SimulationRow WHERE simulationID = 1"), last);
  EXPECT_EQ(QueryInt("SELECT COUNT(*) FROM LogGap"), 0);
  viewer->Signal(SIGTERM);
  EXPECT_EQ(viewer->Wait(std::chrono::seconds(60)).value_or(-1), 0) << ReadText(dir_ / "viewer.log");
  logger->Signal(SIGTERM);
  EXPECT_EQ(logger->Wait(std::chrono::seconds(60)).value_or(-1), 0) << ReadText(dir_ / "logger.log");
}

// The sim's part on the MuJoCo engine, without a logger or viewer: the
// corpus must not stop its stepping or its refusing (the ODE sim meets it
// above, beside the logger and the viewer).
class HostileSimTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_hostile_sim_"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(HostileSimTest, TheMujocoSimSurvivesTheCorpusAndKeepsWorking) {
  const std::string url = test_support::BusUrl(1);
  Observer bus(url);
  ChildProcess sim(test_support::SimCommand(sim::testing::WriteArmWorld(dir_), url,
                                            {"--statusPeriod=0.2", test_support::EngineFlag("mujoco")}),
                   (dir_ / "sim.log").string());
  ASSERT_TRUE(bus.Until([&] { return bus.last_step > 100; }, 20)) << ReadText(dir_ / "sim.log");
  int undecodable_for_sim = 0;
  ASSERT_NO_FATAL_FAILURE(
      SendCorpus(bus, {{"simpartner-sim", &sim, dir_ / "sim.log"}}, &undecodable_for_sim));
  ASSERT_NO_FATAL_FAILURE(ExpectSimStillWorks(bus, undecodable_for_sim, dir_ / "sim.log"));
  EXPECT_TRUE(bus.Until([&] { return bus.status.engine == "mujoco"; }, 2)) << bus.status.engine;
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Wait(std::chrono::seconds(10)).value_or(-1), 0) << ReadText(dir_ / "sim.log");
}

}  // namespace
}  // namespace simpartner
