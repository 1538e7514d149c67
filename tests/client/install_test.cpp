// `cmake --install` gives an outside project what it needs: a project in
// its own tree (tests/client/outside_project) finds the package in a
// temporary prefix, builds, and turns a wheel of a real sim.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>

#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "client_test_support.h"
#include "simpartner/client/client.h"

namespace simpartner::client {
namespace {

using testing::NumberAfter;
using test_support::ReadText;
using test_support::ShippedWorld;
using test_support::SimProcess;
using test_support::FreshTestDir;
using test_support::BusUrl;

// The exit status of args run to its end (-1 after `seconds`), its output in `log`.
int RunLogged(const std::vector<std::string>& args, const std::string& log, int seconds = 300) {
  return test_support::RunToEnd(args, log, std::chrono::seconds(seconds)).status;
}

TEST(Install, OutsideProjectBuildsAgainstTheInstallTreeAndDrivesTheSim) {
  const auto dir = FreshTestDir("sp_client_");
  const std::string prefix = (dir / "prefix").string();
  const std::string build = (dir / "build").string();
  const std::string log = (dir / "steps.log").string();
  ASSERT_EQ(test_support::InstallThisBuild(prefix, "client", log).status, 0) << ReadText(log);
  // What an outside project includes: the client, the generated messages.
  for (const char* file : {"include/simpartner/client/client.h", "include/simpartner/command_t.hpp",
                           "include/simpartner/lcm_schema.hpp", "include/simpartner/bus_decode.h",
                           "lib/cmake/SimPartner/SimPartnerConfig.cmake"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(prefix) / file)) << file;
  // The installed package names no path of this build or source tree, so
  // the prefix can move (or the build be deleted).
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(prefix) / "lib/cmake/SimPartner")) {
    const std::string text = ReadText(entry.path().string());
    EXPECT_EQ(text.find(SP_BINARY_DIR), std::string::npos) << entry.path();
    EXPECT_EQ(text.find(std::string(SP_SOURCE_DIR) + "/"), std::string::npos) << entry.path();
  }
  // The README's first controller, as printed, but on this test's bus.
  const std::string url = BusUrl(31);
  const std::string readme = ReadText(std::string(SP_SOURCE_DIR) + "/README.md");
  std::string controller;
  for (size_t open = readme.find("```cpp\n"); open != std::string::npos && controller.empty();
       open = readme.find("```cpp\n", open + 1)) {
    const size_t begin = open + 7;
    const size_t close = readme.find("```", begin);
    if (close == std::string::npos) break;
    const std::string code = readme.substr(begin, close - begin);
    if (code.find("Client sim;") != std::string::npos) controller = code;
  }
  ASSERT_FALSE(controller.empty()) << "README.md has no controller example with 'Client sim;'";
  const size_t at = controller.find("Client sim;");
  controller.replace(at, std::string("Client sim;").size(),
                     "ClientOptions o; o.url = \"" + url + "\"; Client sim(o);");
  const std::string controller_file = (dir / "first_controller.cpp").string();
  std::ofstream(controller_file) << controller;

  const std::string configure_log = (dir / "configure.log").string();
  ASSERT_EQ(RunLogged({SP_CMAKE, "-S", std::string(SP_SOURCE_DIR) + "/tests/client/outside_project",
                       "-B", build, "-G", SP_GENERATOR, "-DCMAKE_PREFIX_PATH=" + prefix,
                       "-DCMAKE_BUILD_TYPE=Release", "-DREADME_CONTROLLER=" + controller_file,
                       std::string("-DCMAKE_CXX_COMPILER=") + SP_OUTSIDE_COMPILER,
                       std::string("-DCMAKE_CXX_FLAGS=") + SP_OUTSIDE_FLAGS,
                       std::string("-DCMAKE_EXE_LINKER_FLAGS=") + SP_OUTSIDE_FLAGS},
                      configure_log),
            0)
      << ReadText(configure_log);
  const std::string build_log = (dir / "build.log").string();
  ASSERT_EQ(RunLogged({SP_CMAKE, "--build", build}, build_log), 0) << ReadText(build_log);

  SimProcess sim(ShippedWorld("gen1_flat.xml"), url, (dir / "sim.log").string(), {"--speed=0"});
  const std::string run_log = (dir / "turn_wheel.log").string();
  ASSERT_EQ(RunLogged({build + "/turn_wheel", url, "Axle2Motor", "1.5"}, run_log, 30), 0)
      << ReadText(run_log);
  EXPECT_NE(ReadText(run_log).find("Axle2Motor accepted at step "), std::string::npos);
  // The installed programs (component programs; those this build has).
  const std::string programs_log = (dir / "programs.log").string();
  ASSERT_EQ(test_support::InstallThisBuild(prefix, "programs", programs_log).status, 0)
      << ReadText(programs_log);
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(prefix) /
                                      "share/simpartner/models/worlds/gen1_flat.xml"));
  const std::string cmd_log = (dir / "cmd.log").string();
  EXPECT_EQ(RunLogged({prefix + "/bin/simpartner-cmd", "--lcm-url", url, "set", "Axle3Motor",
                       "1000,-0.5"},
                      cmd_log, 30),
            0)
      << ReadText(cmd_log);
  // The effect, seen on the bus: wheel 2's joint turns at 1.5 rad/s.
  ClientOptions o;
  o.url = url;
  o.program = "install_test";
  o.model_timeout = 10;
  Client client(o);
  const state_t s = client.WaitUntilSimTime(client.LatestState()->sim_time + 0.5, 10);
  EXPECT_NEAR(s.joints[static_cast<size_t>(client.catalog()->JointIndex("Axle2"))].rate[0], 1.5,
              0.1);
  EXPECT_NEAR(s.joints[static_cast<size_t>(client.catalog()->JointIndex("Axle3"))].rate[0], -0.5,
              0.1);

  // The README's controller: all four wheels at 2 rad/s for 3 s of sim
  // time, on 0.235 m wheels (SPEC 7): the front half 1.41 m further on.
  const double x0 = client.model()->bodies[static_cast<size_t>(
                                               client.catalog()->BodyIndex("FrontChassis"))]
                        .initial_position[0];
  const std::string first_log = (dir / "first_controller.log").string();
  ASSERT_EQ(RunLogged({build + "/first_controller"}, first_log, 60), 0) << ReadText(first_log);
  const std::string printed = ReadText(first_log);
  const std::optional<double> front_x = NumberAfter(printed, "front is at x = ");
  ASSERT_TRUE(front_x) << printed;
  EXPECT_NEAR(*front_x - x0, 3 * 2.0 * 0.235, 0.15) << printed;
  if (!::testing::Test::HasFailure()) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace simpartner::client
