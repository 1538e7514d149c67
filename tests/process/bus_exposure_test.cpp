// Who can reach the bus, said at start (common/bus_exposure.h): a sim in a
// network namespace whose only outward interface is a veth (standing for
// eth0) warns once on an unsigned bus (SIMPARTNER_BUS_KEY=none), naming
// it and the ways out; with the link down (only loopback), with
// SIMPARTNER_BUS_EXPOSURE_SAID=1 (scripts/run dealt with it) or signed
// (the default, or a key file) it does not. Root only (it makes
// namespaces).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "../support/netns.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "simpartner/bus_signing.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

class BusExposureTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_exposure_", 30); }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // simpartner-sim for 0.05 s in the host's namespace, with `environment`
  // ("NAME=VALUE" each) set and nothing of the test's own that changes
  // what it says; what it printed.
  std::string RunSim(const test_support::NamespaceLan& lan, std::vector<std::string> environment) {
    std::vector<std::string> argv = {"env", "-u", "SIMPARTNER_BUS_EXPOSURE_SAID", "-u",
                                     "SIMPARTNER_BUS_KEY"};
    argv.insert(argv.end(), environment.begin(), environment.end());
    const std::vector<std::string> sim = test_support::SimCommand(
        test_support::ShippedWorld("pendulum.xml"), "udpm://239.255.76.67:7667?ttl=0",
        {"--duration=0.05"});
    argv.insert(argv.end(), sim.begin(), sim.end());
    const test_support::ProgramRun run = test_support::RunToEnd(
        lan.Exec("host", argv), (dir_ / ("sim" + std::to_string(++runs_) + ".log")).string(),
        std::chrono::seconds(30));
    EXPECT_EQ(run.status, 0) << run.output;
    return run.output;
  }
  fs::path dir_;
  int runs_ = 0;
};

TEST_F(BusExposureTest, ASimOnAnOpenBusSaysSoOnceAndNotWhenClosedOrSigned) {
  ASSERT_EQ(::geteuid(), 0u) << "this test makes network namespaces and needs root";
  test_support::NamespaceLan lan("spx", {"host"});
  const std::string veth = lan.Interface("host") + " " + lan.Address("host");
  const std::string none = std::string(kBusKeyVariable) + "=" + kNoBusKey;
  const std::string open = RunSim(lan, {none});
  EXPECT_NE(open.find("warning: the bus udpm://239.255.76.67:7667?ttl=0 takes datagrams from any "
                      "machine on " + veth),
            std::string::npos)
      << open;
  EXPECT_NE(open.find("'sudo scripts/bus-guard on 7667', or sign it (leave SIMPARTNER_BUS_KEY "
                      "unset, or name a key file)"),
            std::string::npos)
      << open;
  EXPECT_NE(open.find("simpartner-sim: the bus is unsigned (SIMPARTNER_BUS_KEY=none)"),
            std::string::npos)
      << open;
  const std::string said = RunSim(lan, {"SIMPARTNER_BUS_EXPOSURE_SAID=1", none});
  EXPECT_EQ(said.find("takes datagrams from any machine"), std::string::npos) << said;
  const std::string key = (dir_ / "bus.key").string();
  std::ofstream(key) << std::string(32, 'k');
  ::chmod(key.c_str(), 0600);
  const std::string signed_bus = RunSim(lan, {"SIMPARTNER_BUS_KEY=" + key});
  EXPECT_EQ(signed_bus.find("takes datagrams from any machine"), std::string::npos) << signed_bus;
  // Nothing configured: signed with the user's key, made now.
  const std::string by_default = RunSim(lan, {"XDG_CONFIG_HOME=" + (dir_ / "config").string()});
  EXPECT_EQ(by_default.find("takes datagrams from any machine"), std::string::npos) << by_default;
  EXPECT_NE(by_default.find("simpartner-sim: made the bus key " +
                            (dir_ / "config" / "simpartner" / "bus.key").string()),
            std::string::npos)
      << by_default;
  // Loopback only (LCM then needs its multicast route there): nobody else
  // can reach the bus.
  lan.SetLink("host", false);
  for (const std::vector<std::string>& ip :
       {std::vector<std::string>{"ip", "link", "set", "lo", "multicast", "on"},
        std::vector<std::string>{"ip", "route", "add", "224.0.0.0/4", "dev", "lo"}})
    ASSERT_EQ(test_support::RunToEnd(lan.Exec("host", ip), (dir_ / "ip.log").string(),
                                     std::chrono::seconds(10))
                  .status,
              0);
  const std::string alone = RunSim(lan, {none});
  EXPECT_EQ(alone.find("takes datagrams from any machine"), std::string::npos) << alone;
}

}  // namespace
}  // namespace simpartner
