// simpartner-batch as a user runs it: real sims, controllers and loggers,
// each run on its own bus. The example batch gives the same state hashes
// 2 at a time and 1 at a time, resumes where it stopped, reports a failed
// run while the others finish, logs every run with its tag into one
// database, and a bad batch file starts nothing.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "../support/mariadb_seed.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/slurm.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "simpartner/child_process.h"
#include "simpartner/logger/db.h"
#include "simpartner/logger/private_server.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;
using test_support::ReadText;

// summary.csv as rows of fields by column name.
std::vector<std::map<std::string, std::string>> Summary(const fs::path& results) {
  std::ifstream in(results / "summary.csv");
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    if (header.empty()) {
      header = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

class BatchProcessTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_batch_", 30); }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  test_support::ProgramRun Batch(const std::vector<std::string>& args, const std::string& log) {
    return test_support::RunToEnd(test_support::BuiltCommand("simpartner-batch", args),
                                  (dir_ / log).string(), std::chrono::minutes(10));
  }
  std::string Example() const {
    return test_support::SourceDir() + "/examples/batches/drive_to_point_sweep.xml";
  }
  // A batch file of the test's own, next to which nothing else is needed.
  std::string Write(const std::string& name, const std::string& body) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << "<batch name=\"" << name.substr(0, name.find('.'))
                        << "\" version=\"1\">\n" << body << "</batch>\n";
    return path.string();
  }
  fs::path dir_;
};

TEST_F(BatchProcessTest, TheExampleRepeatsAtAnyParallelismAndResumes) {
  const fs::path two = dir_ / "two", one = dir_ / "one";
  const test_support::ProgramRun a =
      Batch({Example(), "--no-log", "--parallel", "2", "--results", two.string()}, "two.log");
  ASSERT_EQ(a.status, 0) << a.output;
  EXPECT_NE(a.output.find("6 run(s) done, 0 failed, 0 done before"), std::string::npos) << a.output;
  const auto rows = Summary(two);
  ASSERT_EQ(rows.size(), 6u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "ok") << row.at("log_dir");
    EXPECT_EQ(row.at("last_step"), "6000");
    EXPECT_EQ(row.at("state_hash").size(), 16u);
  }
  // Friction changes the run: the same goal on 0.5 and 1.0 is another run.
  EXPECT_NE(rows[0].at("state_hash"), rows[3].at("state_hash"));

  const test_support::ProgramRun b =
      Batch({Example(), "--no-log", "--parallel", "1", "--results", one.string()}, "one.log");
  ASSERT_EQ(b.status, 0) << b.output;
  const auto again = Summary(one);
  ASSERT_EQ(again.size(), 6u);
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(again[i].at("state_hash"), rows[i].at("state_hash")) << "run " << i;
    EXPECT_EQ(again[i].at("front_x"), rows[i].at("front_x")) << "run " << i;
  }

  // An interrupted batch: run 4's result lost. Again, only run 4 runs.
  fs::remove(two / "runs/4/result.txt");
  const test_support::ProgramRun c =
      Batch({Example(), "--no-log", "--results", two.string()}, "resume.log");
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("1 run(s) done, 0 failed, 5 done before"), std::string::npos) << c.output;
  EXPECT_EQ(Summary(two)[4].at("state_hash"), rows[4].at("state_hash"));
}

TEST_F(BatchProcessTest, AFailedRunIsReportedAndTheOthersFinish) {
  // period -1: drive_to_point refuses its command line (exit 2).
  const std::string file = Write("failing.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>1</duration>\n"
      "  <controller>drive_to_point --lcm-url {url} --x 2 --period {p}</controller>\n"
      "  <sweep><vary name=\"p\" values=\"10 -1 5\"/></sweep>\n");
  const fs::path results = dir_ / "results";
  const test_support::ProgramRun run =
      Batch({file, "--no-log", "--results", results.string(), "--timeout", "60"}, "batch.log");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("run 1 (batch=failing run=1 p=-1) failed: controller exit 2"),
            std::string::npos)
      << run.output;
  const auto rows = Summary(results);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("status"), "ok");
  EXPECT_EQ(rows[2].at("status"), "ok");
  EXPECT_NE(rows[1].at("status").find("controller exit 2"), std::string::npos);
  // Its logs stay where the summary says.
  EXPECT_NE(ReadText(fs::path(rows[1].at("log_dir")) / "controller.log").find("--period"),
            std::string::npos);
}

TEST_F(BatchProcessTest, EveryRunIsLoggedIntoOneDatabaseWithItsValues) {
  logger::PrivateServer server(test_support::SourceDir() + "/scripts/mariadb",
                               (dir_ / "db").string(), false, test_support::MariaDbSeed());
  server.Start();
  const std::string file = Write("logged.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>1</duration>\n"
      "  <controller>drive_to_point --lcm-url {url} --x {gx} --period 10</controller>\n"
      "  <sweep><vary name=\"gx\" values=\"2 3\"/></sweep>\n");
  // The database and server named as a user names them: the loggers take
  // them as parameters (--dbname=X), which they refused as --dbname X.
  const test_support::ProgramRun run =
      Batch({file, "--db-options", server.logger_options(), "--dbname", "simpartner_batch",
             "--dbserver", server.socket(), "--parallel", "2", "--results",
             (dir_ / "results").string()},
            "batch.log");
  EXPECT_EQ(run.status, 0) << run.output;
  auto db = logger::DbConnection::Open(server.AdminTarget("simpartner_batch"), false);
  db->UseDatabase(false);
  for (const char* gx : {"2", "3"}) {
    const std::string tag = std::string("batch=logged run=") + (gx[0] == '2' ? "0" : "1") +
                            " gx=" + gx;
    const int64_t steps = db->QueryInt(
        "SELECT (SELECT COUNT(*) FROM SimulationRow r WHERE r.simulationID = s.simulationID) "
        "FROM Simulation s WHERE s.tag = '" + tag + "'",
        "steps of " + tag, -1);
    EXPECT_EQ(steps, 1000) << tag << "\n" << run.output;
  }
  server.Stop();
}

// A run whose controller fails at once (false: exit 1) leaves its
// Simulation row closed: the logger, stopped with the sim, still reads the
// sim's end from what its socket holds (an audit found such rows open
// before the logger did).
TEST_F(BatchProcessTest, AFailedRunLeavesNoOpenSimulation) {
  logger::PrivateServer server(test_support::SourceDir() + "/scripts/mariadb",
                               (dir_ / "db").string(), false, test_support::MariaDbSeed());
  server.Start();
  const std::string file = Write("failing.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>1</duration>\n"
      "  <controller>false --lcm-url {url}</controller>\n");
  const test_support::ProgramRun run =
      Batch({file, "--db-options", server.logger_options(), "--results", (dir_ / "results").string()},
            "batch.log");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("0 run(s) done, 1 failed"), std::string::npos) << run.output;
  auto db = logger::DbConnection::Open(server.AdminTarget("simpartner"), false);
  db->UseDatabase(false);
  EXPECT_EQ(db->QueryInt("SELECT COUNT(*) FROM Simulation", "runs logged", -1), 1) << run.output;
  EXPECT_EQ(db->QueryInt("SELECT COUNT(*) FROM Simulation WHERE endTime IS NULL", "open runs", -1), 0)
      << run.output;
  server.Stop();
}

// The batch paces each sim (a lock-step controller of its own): a batch
// process that gets no CPU for 2 s (SIGSTOP, as a loaded node does to it)
// loses no state, and the run's hash is whole. Without the pacing the sim
// ran on at full speed, the socket buffer overflowed and the batch saw
// states only up to step 949 of 10,000: no hash.
TEST_F(BatchProcessTest, ABatchThatGetsNoCpuForAWhileLosesNoState) {
  const std::string file = Write("stall.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>10</duration>\n"
      "  <controller>drive_to_point --lcm-url {url} --x 3 --period 10</controller>\n");
  const fs::path results = dir_ / "results";
  ChildProcess batch(test_support::BuiltCommand("simpartner-batch",
                                                {file, "--no-log", "--results", results.string()}),
                     (dir_ / "batch.log").string());
  // The controller starts once the sim is up and paced.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(results / "runs" / "0" / "controller.log") &&
         std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  batch.Signal(SIGSTOP);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  batch.Signal(SIGCONT);
  ASSERT_EQ(batch.Wait(std::chrono::minutes(5)), std::optional<int>(0))
      << ReadText((dir_ / "batch.log").string());
  const auto rows = Summary(results);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("status"), "ok");
  EXPECT_EQ(rows[0].at("last_step"), "10000");
  EXPECT_EQ(rows[0].at("state_hash").size(), 16u) << "a state was lost";
}

// Every process below `pid` (children, theirs, ...), from /proc.
std::vector<pid_t> Descendants(pid_t pid) {
  std::vector<pid_t> found;
  std::vector<pid_t> todo = {pid};
  while (!todo.empty()) {
    const pid_t parent = todo.back();
    todo.pop_back();
    for (const auto& task : fs::directory_iterator("/proc/" + std::to_string(parent) + "/task",
                                                   std::filesystem::directory_options::skip_permission_denied)) {
      std::ifstream children(task.path() / "children");
      for (pid_t child; children >> child;) {
        found.push_back(child);
        todo.push_back(child);
      }
    }
  }
  return found;
}

// A controller that starts a helper (here `sleep`) and writes its pid
// next to itself, then drives: at the run's end the helper is stopped with
// it, not left running after the batch (an audit found 8 such).
TEST_F(BatchProcessTest, AControllersHelpersEndWithItsRun) {
  const fs::path controller = dir_ / "fork_then_drive.sh";
  std::ofstream(controller) << "#!/bin/sh\nsleep 600 &\necho $! > \"" << (dir_ / "helper.pid").string()
                            << "\"\nexec " << test_support::BuiltProgram("drive_to_point") << " \"$@\"\n";
  fs::permissions(controller, fs::perms::owner_all);
  const std::string file = Write("helpers.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>2</duration>\n"
      "  <controller>" + controller.string() + " --lcm-url {url} --x 1 --period 10</controller>\n");
  const test_support::ProgramRun run =
      Batch({file, "--no-log", "--results", (dir_ / "results").string()}, "batch.log");
  EXPECT_EQ(run.status, 0) << run.output;
  const pid_t helper = static_cast<pid_t>(std::stol(ReadText(dir_ / "helper.pid")));
  ASSERT_GT(helper, 0);
  const bool helper_ran_on = test_support::ProcessRunning(helper);
  if (helper_ran_on) ::kill(helper, SIGKILL);
  EXPECT_FALSE(helper_ran_on) << "the controller's helper (pid " << helper << ") outlived the batch";
}

// kill -9 of the batch cannot run its stop: the kernel sends each process
// it started SIGTERM (the controller's group goes with the controller).
TEST_F(BatchProcessTest, AKilledBatchTakesItsProcessesWithIt) {
  const std::string file = Write("killed.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>600</duration>\n"
      "  <controller>drive_to_point --lcm-url {url} --x 100 --period 10</controller>\n");
  const fs::path results = dir_ / "results";
  ChildProcess batch(test_support::BuiltCommand("simpartner-batch", {file, "--no-log", "--results", results.string()}),
                     (dir_ / "batch.log").string());
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(results / "runs" / "0" / "controller.log") && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const std::vector<pid_t> started = Descendants(batch.pid());
  ASSERT_GE(started.size(), 2u) << "the sim and the controller" << ReadText(dir_ / "batch.log");
  batch.Signal(SIGKILL);
  ASSERT_EQ(batch.Wait(std::chrono::seconds(10)), std::optional<int>(128 + SIGKILL));
  std::vector<pid_t> left;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(15);
  do {
    left.clear();
    for (const pid_t pid : started)
      if (test_support::ProcessRunning(pid)) left.push_back(pid);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  } while (!left.empty() && std::chrono::steady_clock::now() < deadline);
  for (const pid_t pid : left) ::kill(pid, SIGKILL);
  EXPECT_TRUE(left.empty()) << left.size() << " of the batch's " << started.size()
                            << " processes ran on after it was killed";
}

// The cluster path on a single-node Slurm of the test's own: the same runs
// (state hashes) as run here, every task logging into the one server the
// batch names.
TEST_F(BatchProcessTest, OnSlurmTheRunsAreTheRunsRunHere) {
  ASSERT_EQ(::geteuid(), 0u) << "the private Slurm runs its daemons as root";
  const std::string file = Write("cluster.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>1.5</duration>\n"
      "  <controller>drive_to_point --lcm-url {url} --x {gx} --period 10</controller>\n"
      "  <sweep><vary name=\"gx\" values=\"2 3 4\"/><vary key=\"contactMu\" values=\"0.6 1\"/>"
      "</sweep>\n");
  const test_support::ProgramRun here =
      Batch({file, "--no-log", "--results", (dir_ / "here").string()}, "here.log");
  ASSERT_EQ(here.status, 0) << here.output;
  test_support::PrivateSlurm slurm(dir_ / "slurm");
  logger::PrivateServer server(test_support::SourceDir() + "/scripts/mariadb",
                               (dir_ / "db").string(), false, test_support::MariaDbSeed());
  server.Start();
  const test_support::ProgramRun there =
      Batch({file, "--db-options", server.logger_options(), "--slurm", "--results",
             (dir_ / "there").string()},
            "there.log");
  ASSERT_EQ(there.status, 0) << there.output;
  EXPECT_NE(there.output.find("slurm job "), std::string::npos) << there.output;
  EXPECT_NE(there.output.find("6 run(s) as array tasks 0,1,2,3,4,5"), std::string::npos)
      << there.output;
  const auto a = Summary(dir_ / "here"), b = Summary(dir_ / "there");
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), 6u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(b[i].at("status"), "ok") << b[i].at("log_dir");
    EXPECT_EQ(b[i].at("state_hash"), a[i].at("state_hash")) << "run " << i;
    EXPECT_EQ(a[i].at("state_hash").size(), 16u);
  }
  auto db = logger::DbConnection::Open(server.AdminTarget("simpartner"), false);
  db->UseDatabase(false);
  EXPECT_EQ(db->QueryInt("SELECT COUNT(*) FROM Simulation WHERE tag LIKE 'batch=cluster run=%'",
                         "tagged runs", -1),
            6);
  EXPECT_EQ(db->QueryInt("SELECT COUNT(*) FROM SimulationRow", "logged steps", -1), 6 * 1500);
  server.Stop();
  // Again: every run is done; nothing is submitted.
  const test_support::ProgramRun again =
      Batch({file, "--no-log", "--slurm", "--results", (dir_ / "there").string()}, "again.log");
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(again.output.find("slurm job "), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("6 done before"), std::string::npos) << again.output;
}

TEST_F(BatchProcessTest, ASlurmThatIsNotThereIsSaidClearly) {
  const std::string file = Write("nowhere.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>1</duration>\n"
      "  <controller>drive_to_point --lcm-url {url}</controller>\n");
  // No sbatch on PATH.
  const test_support::ProgramRun no_client = test_support::RunToEnd(
      {"/usr/bin/env", "PATH=/nonexistent", test_support::BuiltProgram("simpartner-batch"), file,
       "--no-log", "--slurm", "--results", (dir_ / "a").string()},
      (dir_ / "no_client.log").string(), std::chrono::seconds(60));
  EXPECT_EQ(no_client.status, 1);
  EXPECT_NE(no_client.output.find("slurm: sbatch is not on PATH"), std::string::npos)
      << no_client.output;
  // A configuration whose controller is not running: an answer, not a hang.
  const fs::path conf = dir_ / "slurm.conf";
  std::ofstream(conf) << "ClusterName=none\nSlurmctldHost=localhost(127.0.0.1)\n"
                         "SlurmctldPort=9\nAuthType=auth/none\nNodeName=localhost\n"
                         "PartitionName=p Nodes=localhost Default=YES\n";
  const auto start = std::chrono::steady_clock::now();
  const test_support::ProgramRun no_server = test_support::RunToEnd(
      {"/usr/bin/env", "SLURM_CONF=" + conf.string(),
       test_support::BuiltProgram("simpartner-batch"), file, "--no-log", "--slurm", "--results",
       (dir_ / "b").string()},
      (dir_ / "no_server.log").string(), std::chrono::seconds(180));
  EXPECT_EQ(no_server.status, 1);
  EXPECT_NE(no_server.output.find("simpartner-batch: slurm: "), std::string::npos)
      << no_server.output;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(120));
}

TEST_F(BatchProcessTest, ABadBatchFileStartsNothing) {
  const std::string file = Write("bad.xml",
      "  <world>gen1_flat.xml</world>\n  <duration>1</duration>\n"
      "  <controller>drive_to_point --lcm-url {url}</controller>\n"
      "  <sweep><vary key=\"contactMoo\" values=\"1\"/></sweep>\n");
  const test_support::ProgramRun run =
      Batch({file, "--no-log", "--results", (dir_ / "results").string()}, "batch.log");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find(file + ":5: vary: unknown key 'contactMoo' (did you mean 'contactMu'?)"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("nothing started"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "results"));
}

}  // namespace
}  // namespace simpartner
