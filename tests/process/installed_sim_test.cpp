// `cmake --install` of this build into a temporary prefix gives programs
// that run from any directory: the installed simpartner-sim finds its
// parameters, worlds and robots under <prefix>/share/simpartner (never in
// this source tree), and a missing world names every path it looked at.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/test_dir.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

using test_support::ProgramRun;

class InstalledSimTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(test_support::FreshTestDir("sp_installed_sim_", 0));
    fs::create_directories(*root_ / "home");
    const ProgramRun install = test_support::InstallThisBuild((*root_ / "prefix").string(), "programs",
                                                              (*root_ / "install.log").string());
    install_status_ = install.status;
    install_log_ = new std::string(install.output);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete install_log_;
  }
  void SetUp() override { ASSERT_EQ(install_status_, 0) << *install_log_; }

  static fs::path Prefix() { return *root_ / "prefix"; }
  static fs::path Home() { return *root_ / "home"; }
  static fs::path Data() { return Prefix() / "share" / "simpartner"; }

  // The installed sim, started in Home() as a user would from ~, without
  // SIMPARTNER_DATA unless data_env is given (env -C: chdir, -u: unset).
  ProgramRun Sim(const std::vector<std::string>& args, const std::string& data_env = "") {
    std::vector<std::string> argv = {"/usr/bin/env", "-C", Home().string(), "-u",
                                     "SIMPARTNER_DATA"};
    if (!data_env.empty()) argv.push_back("SIMPARTNER_DATA=" + data_env);
    argv.push_back((Prefix() / "bin" / "simpartner-sim").string());
    argv.insert(argv.end(), args.begin(), args.end());
    const fs::path log = *root_ / ("sim_" + std::to_string(++runs_) + ".log");
    return test_support::RunToEnd(argv, log.string(), std::chrono::seconds(30));
  }

  static fs::path* root_;
  static int install_status_;
  static std::string* install_log_;
  int runs_ = 0;
};

fs::path* InstalledSimTest::root_ = nullptr;
int InstalledSimTest::install_status_ = -1;
std::string* InstalledSimTest::install_log_ = nullptr;

TEST_F(InstalledSimTest, InstallsTheDataInTheSourceTreesLayout) {
  for (const char* file :
       {"bin/simpartner-sim", "bin/simpartner-teleop-vpad", "share/simpartner/parameters.txt",
        "share/simpartner/models/worlds/flat_ground.xml",
        "share/simpartner/models/robots/workpartner_gen4.xml",
        "share/simpartner/models/dtd/world.dtd", "share/simpartner/models/soils/wong2008.xml",
        "share/simpartner/models/dtd/soils.dtd", "share/simpartner/sequences/gen3_pole_task.xml",
        "share/simpartner/sequences/dtd/sequence_v2.dtd",
        "share/simpartner/teleop/mappings/workpartner_gen3.map",
        "share/java/simpartner_lcmtypes.jar"})
    EXPECT_TRUE(fs::is_regular_file(Prefix() / file)) << file << "\n" << *install_log_;
}

TEST_F(InstalledSimTest, CheckFromAnotherDirectoryUsesTheInstalledData) {
  const ProgramRun run = Sim({"--check"});
  EXPECT_EQ(run.status, 0) << run.output;
  // The default world of the installed parameters.txt, and its robot.
  EXPECT_NE(run.output.find("world 'FlatGround' (" + (Data() / "models/worlds/flat_ground.xml").string() +
                            ")"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("(" + (Data() / "models/robots/workpartner_gen3.xml").string() + ")"),
            std::string::npos)
      << run.output;
  // An installed program never reads the tree it was built from.
  EXPECT_EQ(run.output.find(std::string(SP_SOURCE_DIR) + "/"), std::string::npos) << run.output;
}

TEST_F(InstalledSimTest, AShippedWorldIsFoundByItsFileName) {
  const ProgramRun run = Sim({"--check", "--environment=gen1_flat.xml"});
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("(" + (Data() / "models/worlds/gen1_flat.xml").string() + ")"),
            std::string::npos)
      << run.output;
}

TEST_F(InstalledSimTest, AShortRunOnAPrivateBusEndsWithItsDuration) {
  const std::string url = test_support::BusUrl(0);
  const ProgramRun run = Sim({"--lcm-url", url, "--duration=0.5", "--speed=0"});
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("simpartner-sim: running"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(url), std::string::npos) << run.output;
}

TEST_F(InstalledSimTest, AMissingWorldListsEveryPathTried) {
  const ProgramRun run = Sim({"--check", "--environment=no_such_world.xml"});
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("no_such_world.xml: cannot read world file: not found; tried:"),
            std::string::npos)
      << run.output;
  for (const fs::path& tried : {Home() / "no_such_world.xml", Data() / "no_such_world.xml",
                                Data() / "models/worlds/no_such_world.xml"})
    EXPECT_NE(run.output.find("  " + tried.string() + " ("), std::string::npos)
        << tried << "\n" << run.output;
  EXPECT_EQ(run.output.find(std::string(SP_SOURCE_DIR) + "/"), std::string::npos) << run.output;
}

// A world of the user's own data directory whose robot path points at a
// robots/ it does not have: the robot comes from the installed data.
TEST_F(InstalledSimTest, SimpartnerDataComesFirstAndRobotsFallBackToTheInstall) {
  const fs::path mine = *root_ / "mine";
  fs::create_directories(mine / "models/worlds");
  fs::copy_file(Data() / "models/worlds/gen1_flat.xml", mine / "models/worlds/my_world.xml",
                fs::copy_options::overwrite_existing);
  const ProgramRun run = Sim({"--check", "--environment=my_world.xml"}, mine.string());
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("(" + (mine / "models/worlds/my_world.xml").string() + ")"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("(" + (Data() / "models/robots/workpartner_gen1.xml").string() + ")"),
            std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace simpartner
