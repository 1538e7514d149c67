// The client library against real simpartner-sim processes on udpm
// (ttl=0): learning the model, commands accepted and refused, readings,
// sim time, run control, no sim, a sim restarting under the client, and
// several threads and clients sending at once.
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <cmath>
#include <thread>

#include <lcm/lcm-cpp.hpp>

#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/hostile_corpus.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/wait.h"
#include "simpartner/channels.h"
#include "simpartner/client/client.h"
#include "simpartner/control_t.hpp"

namespace simpartner::client {
namespace {

using test_support::ShippedWorld;
using test_support::SimProcess;
using test_support::FreshTestDir;
using test_support::BusUrl;
using Clock = std::chrono::steady_clock;

ClientOptions Options(const std::string& url, const std::string& program = "client_test") {
  ClientOptions o;
  o.url = url;
  o.program = program;
  o.model_timeout = 10.0;
  o.reply_timeout = 5.0;
  return o;
}

class ClientProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    name_ = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = FreshTestDir("sp_client_");
  }
  void TearDown() override {
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }
  std::string Log(const std::string& file) const { return (dir_ / file).string(); }
  std::string name_;
  std::filesystem::path dir_;
};

// gen2 facing a wall 5.335 m from its scanner (SPEC 8), in real time.
TEST_F(ClientProcessTest, CommandsReadingsAndSimTime) {
  const std::string url = BusUrl(1);
  SimProcess sim(ShippedWorld("scanner_wall.xml"), url, Log("sim.log"));
  Client client(Options(url));
  const auto catalog = client.catalog();
  EXPECT_EQ(catalog->world_name(), "ScannerWall");
  EXPECT_EQ(client.Find("1028").name, "Axle1Motor");
  EXPECT_EQ(client.Find("WorkPartner/Scanner").kind_name(), "scanner");

  // SPEC 4: every actuator starts holding with 1000 per axis; the axle is
  // the z slot, so the setting replaced reads 0,0,1000.
  const command_reply_t reply = client.Command(SetVelocity(client.Find("Axle1Motor"), {2.0}));
  EXPECT_TRUE(reply.accepted);
  EXPECT_EQ(reply.target, "Axle1Motor");
  EXPECT_EQ(reply.previous_text, "0,0,1000");
  EXPECT_GE(reply.applied_at_step, 0);
  // Half a second of sim time later the wheel turns at the commanded rate.
  const int axle = catalog->JointIndex("Axle1");
  const state_t later = client.WaitUntilSimTime(
      (reply.applied_at_step + 500) * catalog->step_size(), 10.0);
  EXPECT_GE(later.sim_time, (reply.applied_at_step + 499) * catalog->step_size());
  EXPECT_NEAR(later.joints[static_cast<size_t>(axle)].rate[0], 2.0, 0.1);
  // The next command replaces it, and says so.
  const command_reply_t again =
      client.Command("Axle1Motor", command_t::ACTION_SET, "1000,1000,500,0,0,0");
  EXPECT_EQ(again.previous_text, "0,0,1000,0,0,2");

  // Refused by the sim, with its reason.
  try {
    client.Command(SetVelocity(client.Find("Axle2Motor"), {5000.0}));
    FAIL() << "5000 rad/s must be refused";
  } catch (const Refused& e) {
    EXPECT_EQ(e.target(), "Axle2Motor");
    EXPECT_NE(e.reason().find("5000"), std::string::npos) << e.reason();
    EXPECT_NE(std::string(e.what()).find("Axle2Motor: refused by the sim: "), std::string::npos);
  }
  EXPECT_THROW(client.Find("Axle2Mottor"), UnknownTarget);

  // A reading on request: the middle ray of 11 sees the wall at 5.335 m.
  const command_reply_t read = client.Command(Read(client.Find("Scanner")));
  const sensor_reading_t scan = client.WaitForReading("Scanner", read.applied_at_step - 1, 5.0);
  ASSERT_EQ(scan.values.size(), 11u);
  EXPECT_NEAR(scan.values[5], 5.335, 0.01);
  ASSERT_TRUE(client.LatestReading("Scanner").has_value());
  EXPECT_EQ(client.LatestReading("Scanner")->step, scan.step);

  // Readings pushed at a rate reach the callback.
  std::atomic<int> calls{0};
  client.OnReading([&](const sensor_reading_t& r) {
    if (r.name == "Scanner") ++calls;
  });
  client.Command(BuildCommand(client.Find("Scanner"), command_t::ACTION_SENSOR_PARAMS, {100}));
  const state_t now = *client.LatestState();
  client.WaitUntilSimTime(now.sim_time + 0.2, 5.0);
  client.OnReading(nullptr);
  EXPECT_GE(calls.load(), 10);  // 100 Hz over 0.2 s of sim time

  EXPECT_LT(client.SecondsSinceHeard(), 0.5);
  EXPECT_EQ(client.BadMessageSummary(), "");
  ASSERT_TRUE(client.LatestStatus().has_value());
  EXPECT_EQ(client.LatestStatus()->simulation_id, catalog->simulation_id());
}

TEST_F(ClientProcessTest, PausedSimAnswersWhenItStepsAndTimesOutMeanwhile) {
  const std::string url = BusUrl(2);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, Log("sim.log"));
  Client client(Options(url));
  client.WaitUntilSimTime(0.05, 10.0);
  client.Pause();
  status_t status = client.WaitForStatus(5.0);
  for (int k = 0; k < 5 && status.run_state != status_t::RUN_PAUSED; ++k)
    status = client.WaitForStatus(5.0);
  ASSERT_EQ(status.run_state, status_t::RUN_PAUSED);
  const auto start = Clock::now();
  const command_t command = SetVelocity(client.Find("Axle1Motor"), {1.0});
  try {
    client.Command(command, 0.5);
    FAIL() << "a paused sim applies (and answers) commands only when it steps";
  } catch (const Timeout& e) {
    EXPECT_DOUBLE_EQ(e.seconds(), 0.5);
    EXPECT_NE(std::string(e.what()).find(url), std::string::npos) << e.what();
  }
  const double waited = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_GE(waited, 0.5);
  EXPECT_LT(waited, 2.0);
  // Stepping applies it: the reply comes, and the sim took exactly 10 steps.
  const int64_t id = client.Send(command);
  const int64_t before = status.step;  // paused there
  client.Step(10);
  const state_t after = client.WaitUntilSimTime((before + 10) * client.catalog()->step_size(), 5.0);
  EXPECT_EQ(after.step, before + 10);
  std::optional<command_reply_t> reply;
  test_support::WaitFor([&] { return (reply = client.TakeReply(id)).has_value(); }, 5,
                        std::chrono::milliseconds(5));
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->accepted);
  // Resume; SetSpeed out of range is refused before sending.
  EXPECT_THROW(client.SetSpeed(1e9), BadValues);
  EXPECT_THROW(client.Step(0), BadValues);
  client.Resume();
  client.WaitUntilSimTime(after.sim_time + 0.1, 5.0);
}

TEST_F(ClientProcessTest, NoSimOnTheBus) {
  ClientOptions o = Options(BusUrl(3));
  o.model_timeout = 0.3;
  const auto start = Clock::now();
  try {
    Client client(o);
    FAIL() << "no sim runs on this port";
  } catch (const NoSim& e) {
    EXPECT_EQ(e.url(), o.url);
    EXPECT_NE(std::string(e.what()).find("no sim on " + o.url), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 2.0);
  ClientOptions bad = o;
  bad.url = "udpm://not-an-address:7667";
  EXPECT_THROW(Client{bad}, ClientError);
}

TEST_F(ClientProcessTest, FollowsASimThatRestartsAndNoticesSilence) {
  const std::string url = BusUrl(4);
  auto first = std::make_unique<SimProcess>(ShippedWorld("gen1_flat.xml"), url, Log("sim1.log"));
  Client client(Options(url));
  const int64_t first_id = client.catalog()->simulation_id();
  client.Command(SetVelocity(client.Find("Axle1Motor"), {1.0}));
  ASSERT_TRUE(first->Stop(std::chrono::seconds(10)).has_value());
  first.reset();
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  EXPECT_GT(client.SecondsSinceHeard(), 0.5);  // what teleop's dead-man check reads
  // No reply from nobody: a timeout, not a hang.
  EXPECT_THROW(client.Command(SetVelocity(client.Find("Axle1Motor"), {1.0}), 0.3), Timeout);

  SimProcess second(ShippedWorld("gen1_flat.xml"), url, Log("sim2.log"));
  test_support::WaitFor([&] { return client.PendingRestart().has_value(); }, 10, std::chrono::milliseconds(10));
  ASSERT_TRUE(client.PendingRestart().has_value());
  EXPECT_EQ(client.PendingRestart()->old_simulation_id(), first_id);
  try {
    client.Send(SetVelocity(client.catalog()->Find("Axle1Motor"), {1.0}));
    FAIL() << "a command for the old sim must not reach the new one";
  } catch (const SimRestarted& e) {
    EXPECT_EQ(e.old_simulation_id(), first_id);
    EXPECT_NE(e.new_simulation_id(), first_id);
  }
  EXPECT_THROW(client.Find("Axle1Motor"), SimRestarted);  // until followed
  const auto catalog = client.Relearn(10.0);
  EXPECT_NE(catalog->simulation_id(), first_id);
  EXPECT_FALSE(client.PendingRestart().has_value());
  client.WaitUntilSimTime(0.0, 10.0);  // a state of the new sim
  EXPECT_LT(client.SecondsSinceHeard(), 0.5);
  // The new sim holds its wheels again: the previous setting is the hold.
  const command_reply_t reply = client.Command(SetVelocity(client.Find("Axle1Motor"), {1.0}));
  EXPECT_EQ(reply.simulation_id, catalog->simulation_id());
  EXPECT_EQ(reply.previous_text, "0,0,1000");
}

TEST_F(ClientProcessTest, ResetLearnsTheNewModel) {
  const std::string url = BusUrl(5);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, Log("sim.log"), {"--speed=0"});
  Client client(Options(url));
  const int64_t old_id = client.catalog()->simulation_id();
  client.WaitUntilSimTime(1.0, 20.0);
  const auto catalog = client.Reset(10.0);
  EXPECT_NE(catalog->simulation_id(), old_id);
  EXPECT_FALSE(client.PendingRestart().has_value());
  const command_reply_t reply = client.Command(SetVelocity(client.Find("Axle1Motor"), {1.0}));
  EXPECT_EQ(reply.simulation_id, catalog->simulation_id());
  // Applied in the new run, which started over at step 0 (as fast as
  // possible, so anywhere in its first seconds).
  const state_t s = client.WaitUntilSimTime(0.0, 5.0);
  EXPECT_EQ(s.simulation_id, catalog->simulation_id());
}

// teleop's pattern: Send at a high rate from other threads while the main
// thread waits for replies; a second client in the same process (same
// sender prefix) never gets the first one's replies.
TEST_F(ClientProcessTest, ConcurrentSendersAndClientsGetTheirOwnReplies) {
  const std::string url = BusUrl(6);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, Log("sim.log"), {"--speed=0"});
  Client a(Options(url, "same"));
  Client b(Options(url, "same"));
  ASSERT_EQ(a.sender(), b.sender());
  std::atomic<int> done{0};
  std::atomic<int> sent{0};
  std::vector<std::thread> senders;
  for (int t = 0; t < 2; ++t) {
    senders.emplace_back([&, t] {
      try {
        const Target motor = a.Find(t == 0 ? "Axle3Motor" : "Axle4Motor");
        for (int n = 0; n < 200; ++n) {
          a.Send(SetVelocity(motor, {0.5}));
          ++sent;
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
      } catch (const std::exception& e) {
        ADD_FAILURE() << "sender " << t << ": " << e.what();
      }
      ++done;
    });
  }
  int refused = 0;
  int k = 0;
  // At least 20 round trips, and on until both senders are through. A
  // failure (a lost reply times out) is reported, and the senders are
  // still joined: an exception past them would abort the whole program.
  try {
    for (; k < 20 || done < 2; ++k) {
      // a: accepted commands for Axle1Motor; b: refused ones for Axle2Motor.
      const command_reply_t ra = a.Command(SetVelocity(a.Find("Axle1Motor"), {0.1 * k}));
      EXPECT_EQ(ra.target, "Axle1Motor");
      EXPECT_TRUE(ra.accepted);
      try {
        b.Command(SetVelocity(b.Find("Axle2Motor"), {2000.0 + k}));
      } catch (const Refused& e) {
        EXPECT_EQ(e.target(), "Axle2Motor");
        EXPECT_NE(e.reason().find(std::to_string(2000 + k)), std::string::npos) << e.reason();
        ++refused;
      }
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "round trip " << k << ": " << e.what();
  }
  for (std::thread& t : senders) t.join();
  EXPECT_EQ(refused, k);
  EXPECT_EQ(sent.load(), 400);
}

// A process with the bus's key (or anyone on the segment, on an unsigned
// bus) can send to the group: every hostile datagram on the channels the
// client reads is counted and ignored, none fakes a restart or replaces
// the state, and the client goes on working.
TEST_F(ClientProcessTest, HostileInputIsCountedAndIgnored) {
  const std::string url = BusUrl(7);
  SimProcess sim(ShippedWorld("scanner_wall.xml"), url, Log("sim.log"));
  Client client(Options(url));
  const auto catalog = client.catalog();
  const size_t bodies = client.model()->bodies.size();
  lcm::LCM attacker(url);
  ASSERT_TRUE(attacker.good());
  test_support::SignedPublisher publisher;
  int sent = 0;
  for (const auto& message : test_support::HostileCorpus(catalog->simulation_id())) {
    const std::string& c = message.channel;
    if (c != channels::kModel && c != channels::kState && c != channels::kStatus &&
        c != channels::kCommandReply && c != channels::kSensor)
      continue;
    publisher.PublishBytes(&attacker, c, message.bytes.data(), message.bytes.size());
    ++sent;
  }
  ASSERT_GT(sent, 15);
  // Everything sent before this reply has been handled by then.
  const command_reply_t reply = client.Command(SetVelocity(client.Find("Axle1Motor"), {1.0}));
  EXPECT_TRUE(reply.accepted);
  const std::string summary = client.BadMessageSummary();
  for (const char* channel : {"SIM_MODEL", "SIM_STATE", "SIM_STATUS", "SIM_SENSOR",
                              "SIM_COMMAND_REPLY"})
    EXPECT_NE(summary.find(channel), std::string::npos) << channel << " in '" << summary << "'";
  EXPECT_FALSE(client.PendingRestart().has_value());
  const state_t s = client.WaitUntilSimTime(client.LatestState()->sim_time + 0.05, 5.0);
  EXPECT_EQ(s.bodies.size(), bodies);
  EXPECT_EQ(s.simulation_id, catalog->simulation_id());
  EXPECT_FALSE(client.LatestReading("Scanner").has_value());  // the forged one was not kept
}

// Commands carry the learned model's simulation id (0 with
// any_simulation); the sim refuses one for another simulation and ignores
// a quit for another simulation.
TEST_F(ClientProcessTest, CommandsCarryTheSimulationIdAndTheSimChecksIt) {
  const std::string url = BusUrl(8);
  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, Log("sim.log"));
  Client client(Options(url));
  const int64_t id = client.catalog()->simulation_id();
  ASSERT_NE(id, 0);
  ClientOptions any = Options(url, "client_test_any");
  any.any_simulation = true;
  Client any_client(any);

  test_support::BusListener listener(url);
  std::vector<command_t> commands;
  std::vector<control_t> controls;
  listener.Keep(channels::kCommand, &commands);
  listener.Keep(channels::kControl, &controls);
  auto pump = [&](size_t command_count, size_t control_count) {
    listener.Until([&] { return commands.size() >= command_count && controls.size() >= control_count; }, 5);
  };

  EXPECT_TRUE(client.Command(SetVelocity(client.Find("Axle1Motor"), {1.0})).accepted);
  EXPECT_TRUE(any_client.Command(SetVelocity(any_client.Find("Axle1Motor"), {0.5})).accepted);
  client.Resume();  // the sim runs already: this changes nothing
  pump(2, 1);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[0].simulation_id, id);
  EXPECT_EQ(commands[1].simulation_id, 0);
  ASSERT_EQ(controls.size(), 1u);
  EXPECT_EQ(controls[0].simulation_id, id);

  // Built by hand for another simulation: refused, and the reply names both.
  command_t elsewhere = SetVelocity(client.Find("Axle1Motor"), {2.0});
  elsewhere.simulation_id = id + 1;
  elsewhere.request_id = 4242;
  elsewhere.sender = "elsewhere@test:1";
  elsewhere.num_values = static_cast<int32_t>(elsewhere.values.size());
  std::optional<command_reply_t> refusal;
  listener.Subscribe<command_reply_t>(channels::kCommandReply, [&](const command_reply_t& r) {
    if (r.sender == "elsewhere@test:1") refusal = r;
  });
  listener.Publish(channels::kCommand, elsewhere);
  listener.Until([&] { return refusal.has_value(); }, 5);
  ASSERT_TRUE(refusal.has_value());
  EXPECT_FALSE(refusal->accepted);
  EXPECT_EQ(refusal->request_id, 4242);
  EXPECT_EQ(refusal->reason, "simulation_id = " + std::to_string(id + 1) +
                                 ": the command is meant for another simulation (this one is " +
                                 std::to_string(id) + ")");

  // A quit for another simulation leaves this one running.
  control_t quit{};
  quit.sender = "elsewhere@test:1";
  quit.simulation_id = id + 1;
  quit.action = control_t::ACTION_QUIT;
  listener.Publish(channels::kControl, quit);
  const double t = client.LatestState()->sim_time;
  client.WaitUntilSimTime(t + 0.5, 5.0);
  EXPECT_TRUE(sim.running()) << sim.Log();
  EXPECT_NE(sim.Log().find("is for simulation_id " + std::to_string(id + 1) + "; this is " +
                           std::to_string(id)),
            std::string::npos)
      << sim.Log();
  client.Quit();  // with its id: this one stops
  EXPECT_EQ(sim.Wait(std::chrono::seconds(10)).value_or(-1), 0) << sim.Log();
}

}  // namespace
}  // namespace simpartner::client
