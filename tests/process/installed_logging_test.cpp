// The whole path of a new user of an installed SimPartner, as docs/install.md
// ("From the installed package to a plot") lists it: `cmake --install` of
// this build into a temporary prefix, then, with HOME a temporary
// directory, the working directory another, the prefix's bin/ on PATH and
// no SIMPARTNER_DATA, SIMPARTNER_STATE or XDG_STATE_HOME:
// simpartner-mariadb start (its files in ~/.local/state/simpartner/mariadb),
// simpartner-logger, simpartner-sim --robot gen4 driven by simpartner-cmd,
// then one simpartner-query plot of a wheel's contact force into a PNG.
// Neither the logger nor the query tool is told where the server is.
// Everything runs for real (MariaDB, LCM on a private udpm port with
// ttl=0); every process is ended by its pid.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/child_process.h"
#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "../support/wait.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;
using test_support::ReadText;

class InstalledLoggingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Short: the server's socket path must fit a unix socket (108 bytes).
    root_ = test_support::FreshTestDir("sp_instlog_", 0);
    fs::create_directories(Home());
    fs::create_directories(Work());
    url_ = test_support::BusUrl(0);
  }

  void TearDown() override {
    // Whatever failed: the processes of this test by their pids (their
    // destructors kill and reap them), then the server, by its script and,
    // should that fail, by the pid in its own pid file.
    children_.clear();
    if (fs::exists(StateDir() / "mariadbd.pid"))
      Run({"simpartner-mariadb", "stop"}, "teardown_stop.log", 90);
    // A server that did not stop, or that started elsewhere under root_
    // (a wrong default directory): ours by its command line, killed by pid.
    for (const fs::directory_entry& e : fs::directory_iterator("/proc")) {
      const std::string name = e.path().filename().string();
      if (name.find_first_not_of("0123456789") != std::string::npos) continue;
      const pid_t pid = static_cast<pid_t>(std::stol(name));
      if (pid != ::getpid() &&
          ReadText(e.path() / "cmdline").find("--defaults-file=" + root_.string() + "/") !=
              std::string::npos)
        ::kill(pid, SIGKILL);
    }
    fs::remove_all(root_);
  }

  fs::path Prefix() const { return root_ / "prefix"; }
  fs::path Home() const { return root_ / "home"; }
  fs::path Work() const { return root_ / "work"; }
  fs::path StateDir() const { return Home() / ".local/state/simpartner/mariadb"; }
  fs::path Log(const std::string& name) const { return root_ / name; }

  // argv as a user types it, in Work(), with the installed bin/ first on
  // PATH and only HOME to say where the user's files go.
  std::vector<std::string> UserCommand(const std::vector<std::string>& args) const {
    std::vector<std::string> argv = {"/usr/bin/env", "-C", Work().string(), "-u", "SIMPARTNER_DATA",
                                     "-u", "SIMPARTNER_STATE", "-u", "XDG_STATE_HOME",
                                     "HOME=" + Home().string(),
                                     "PATH=" + (Prefix() / "bin").string() + ":/usr/bin:/bin"};
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
  }

  // Runs a command to its end; its exit status (-1 after timeout seconds).
  int Run(const std::vector<std::string>& args, const std::string& log, int timeout) {
    return test_support::RunToEnd(UserCommand(args), Log(log).string(), std::chrono::seconds(timeout)).status;
  }

  ChildProcess* Start(const std::vector<std::string>& args, const std::string& log) {
    children_.push_back(std::make_unique<ChildProcess>(UserCommand(args), Log(log).string()));
    return children_.back().get();
  }

  fs::path root_;
  std::string url_;
  std::vector<std::unique_ptr<ChildProcess>> children_;
};

TEST_F(InstalledLoggingTest, StartTheServerLogADrivenGen4RunAndPlotAWheelsForce) {
  {
    const test_support::ProgramRun install =
        test_support::InstallThisBuild(Prefix().string(), "programs", Log("install.log").string());
    ASSERT_EQ(install.status, 0) << install.output;
  }
  ASSERT_TRUE(fs::is_regular_file(Prefix() / "bin/simpartner-mariadb"));
  ASSERT_TRUE(fs::is_regular_file(Prefix() / "share/simpartner/scripts/lib/cli.sh"));

  // Its help says where its files go, also when run through a symlink.
  fs::create_directories(Home() / "bin");
  fs::create_symlink(Prefix() / "bin/simpartner-mariadb", Home() / "bin/my-mariadb");
  ASSERT_EQ(Run({(Home() / "bin/my-mariadb").string(), "--help"}, "help.log", 20), 0)
      << ReadText(Log("help.log"));
  EXPECT_NE(ReadText(Log("help.log")).find("DIR defaults to " + StateDir().string()),
            std::string::npos)
      << ReadText(Log("help.log"));

  // No server yet: the query tool names the places it looked and what to run.
  EXPECT_EQ(Run({"simpartner-query", "list"}, "query_before.log", 20), 2)
      << ReadText(Log("query_before.log"));
  const std::string before = ReadText(Log("query_before.log"));
  EXPECT_NE(before.find("  " + (StateDir() / "reader.cnf").string() + " ($HOME/.local/state)"),
            std::string::npos)
      << before;
  EXPECT_NE(before.find("simpartner-mariadb start"), std::string::npos) << before;

  // docs/install.md, "From the installed package to a plot": the commands a
  // user types.
  ASSERT_EQ(Run({"simpartner-mariadb", "start"}, "mariadb_start.log", 90), 0)
      << ReadText(Log("mariadb_start.log"));
  ASSERT_TRUE(fs::is_regular_file(StateDir() / "logger.cnf")) << ReadText(Log("mariadb_start.log"));
  ASSERT_TRUE(fs::is_regular_file(StateDir() / "reader.cnf"));

  ChildProcess* logger = Start({"simpartner-logger", "--lcm-url", url_}, "logger.log");
  ASSERT_TRUE(test_support::WaitForText(Log("logger.log"), ": logging udpm://", 30))
      << ReadText(Log("logger.log"));
  // The logger found the private server without being told (and is no
  // program of the build tree: it never looks at the source tree's state/).
  EXPECT_NE(ReadText(Log("logger.log")).find((StateDir() / "mysqld.sock").string()),
            std::string::npos)
      << ReadText(Log("logger.log"));

  ChildProcess* sim = Start({"simpartner-sim", "--robot", "gen4", "--duration=2", "--lcm-url", url_},
                            "sim.log");
  // Drive wheel 1 at 3 rad/s: the command waits (--timeout) for the sim.
  EXPECT_EQ(Run({"simpartner-cmd", "--lcm-url", url_, "--timeout", "10", "set", "Axle1Motor", "300,3"},
                "cmd.log", 30),
            0)
      << ReadText(Log("cmd.log")) << ReadText(Log("sim.log"));
  ASSERT_EQ(sim->Wait(std::chrono::seconds(60)).value_or(-1), 0) << ReadText(Log("sim.log"));
  const std::string sim_log = ReadText(Log("sim.log"));
  EXPECT_NE(sim_log.find("WorkPartner gen4 (" +
                         (Prefix() / "share/simpartner/models/robots/workpartner_gen4.xml").string()),
            std::string::npos)
      << sim_log;
  EXPECT_NE(sim_log.find("commands 1 accepted"), std::string::npos) << sim_log;

  logger->Signal(SIGINT);
  ASSERT_EQ(logger->Wait(std::chrono::seconds(60)).value_or(-1), 0) << ReadText(Log("logger.log"));

  ASSERT_EQ(Run({"simpartner-query", "plot", "wheel-forces", "last", "--body", "Wheel1", "-o",
                 "wheel1.png"},
                "plot.log", 60),
            0)
      << ReadText(Log("plot.log"));
  const fs::path png = Work() / "wheel1.png";
  ASSERT_TRUE(fs::is_regular_file(png)) << ReadText(Log("plot.log"));
  const std::string bytes = ReadText(png);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_GT(bytes.size(), 5000u);
  EXPECT_LT(bytes.size(), 5000000u);
  EXPECT_NE(ReadText(Log("plot.log")).find("Wheel1"), std::string::npos) << ReadText(Log("plot.log"));

  EXPECT_EQ(Run({"simpartner-mariadb", "stop"}, "mariadb_stop.log", 90), 0)
      << ReadText(Log("mariadb_stop.log"));
  EXPECT_EQ(Run({"simpartner-mariadb", "status"}, "mariadb_status.log", 20), 3)
      << ReadText(Log("mariadb_status.log"));
  // Nothing was written into the working directory but the plot: the
  // logger's spool is beside the server's files.
  std::vector<std::string> written;
  for (const fs::directory_entry& e : fs::directory_iterator(Work()))
    written.push_back(e.path().filename().string());
  EXPECT_EQ(written, std::vector<std::string>{"wheel1.png"});
  EXPECT_TRUE(fs::is_directory(Home() / ".local/state/simpartner/logger-spool"));
}

}  // namespace
}  // namespace simpartner
