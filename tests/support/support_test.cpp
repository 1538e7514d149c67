// The test support itself: buses of their own, the built programs found,
// messages decoded as the processes decode them, programs run to their end.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <vector>

#include "bus_listener.h"
#include "bus_url.h"
#include "encode.h"
#include "processes.h"
#include "programs.h"
#include "simpartner/channels.h"
#include "simpartner/control_t.hpp"
#include "test_dir.h"
#include "wait.h"

namespace simpartner::test_support {
namespace {

int PortOf(const std::string& url) {
  const size_t colon = url.rfind(':'), query = url.find('?');
  return std::stoi(url.substr(colon + 1, query - colon - 1));
}

TEST(BusUrl, EachOffsetItsOwnPortAndABoundPortIsPassedOver) {
  const std::string a = BusUrl(5), b = BusUrl(6);
  EXPECT_NE(PortOf(a), PortOf(b));
  EXPECT_EQ(a.rfind("udpm://239.255.76.67:", 0), 0u) << a;
  EXPECT_NE(a.find("ttl=0"), std::string::npos) << a;
  EXPECT_NE(a.find("recv_buf_size=4194304"), std::string::npos) << a;
  // Held as LCM holds its receiving port (SO_REUSEADDR): another one.
  const int holder = ::socket(AF_INET, SOCK_DGRAM, 0);
  const int yes = 1;
  ASSERT_EQ(::setsockopt(holder, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes), 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  address.sin_port = htons(static_cast<uint16_t>(PortOf(a)));
  ASSERT_EQ(::bind(holder, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  const std::string again = BusUrl(5);
  ::close(holder);
  EXPECT_NE(PortOf(again), PortOf(a));
  EXPECT_NE(PortOf(again), PortOf(b));
  EXPECT_THROW(BusUrl(-1), std::invalid_argument);
  EXPECT_THROW(BusUrl(100), std::invalid_argument);
}

TEST(BuiltProgram, FoundInItsFolderOfTheBuildTree) {
  EXPECT_EQ(BuiltProgram("simpartner-sim"), BinaryDir() + "/sim_core/simpartner-sim");
  EXPECT_TRUE(std::filesystem::is_regular_file(BuiltProgram("simpartner-sim")));
  try {
    BuiltProgram("simpartner-simm");
    FAIL() << "an unknown program was given a path";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no program 'simpartner-simm'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("simpartner-viewer"), std::string::npos) << e.what();
  }
}

// Signed with the tests' key, as processes sign: what the listener sends
// it hears back (ttl=0 loops back); garbage, signed, and a message
// without a signature are refused and counted.
TEST(BusListener, KeepsWhatDecodesAndCountsWhatDoesNot) {
  BusListener bus(BusUrl(7));
  ASSERT_NE(bus.signer(), nullptr) << "the tests run on a signed bus (tests/CMakeLists.txt)";
  std::vector<control_t> controls;
  bus.Keep(channels::kControl, &controls);
  control_t pause{};
  pause.action = control_t::ACTION_PAUSE;
  pause.sender = "support_test";
  bus.Publish(channels::kControl, pause);
  const uint8_t garbage[] = {1, 2, 3};
  bus.PublishBytes(channels::kControl, garbage, sizeof garbage);
  bus.lcm().publish(channels::kControl, &pause);  // unsigned
  ASSERT_TRUE(bus.Until([&] { return !controls.empty() && bus.refused().total() == 2; }, 5));
  bus.Pump(0.2);
  ASSERT_EQ(controls.size(), 1u);
  EXPECT_EQ(controls[0].sender, "support_test");
  EXPECT_EQ(controls[0].action, control_t::ACTION_PAUSE);
  EXPECT_EQ(bus.refused().count(channels::kControl), 2u);
  EXPECT_FALSE(bus.Until([] { return false; }, 0.05));
}

// A condition that costs 50 ms (a database query, say) is looked at once
// per batch of waiting messages: 200 messages are read within 2 s, where
// one look per message would take 10 s.
TEST(BusListener, ACostlyConditionDoesNotLetTheQueueGrow) {
  BusListener bus(BusUrl(8));
  std::vector<control_t> controls;
  bus.Keep(channels::kControl, &controls);
  control_t step{};
  step.action = control_t::ACTION_STEP;
  step.sender = "support_test";
  constexpr size_t kMessages = 200;
  for (size_t i = 0; i < kMessages; ++i) bus.Publish(channels::kControl, step);
  const auto costly = [&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return controls.size() == kMessages;
  };
  EXPECT_TRUE(bus.Until(costly, 2)) << controls.size() << " of " << kMessages << " read";
}

TEST(Encode, WritesWhatTheDecoderReads) {
  control_t c{};
  c.action = control_t::ACTION_STEP;
  c.steps = 42;
  c.sender = "x";
  const std::vector<uint8_t> bytes = Encode(c);
  EXPECT_EQ(bytes.size(), static_cast<size_t>(c.getEncodedSize()));
  control_t back;
  ASSERT_EQ(back.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  EXPECT_EQ(back.steps, 42);
  EXPECT_EQ(back.sender, "x");
}

TEST(RunToEnd, StatusOutputAndTimeout) {
  const std::filesystem::path dir = FreshTestDir("sp_support_");
  const ProgramRun done = RunToEnd({"/bin/sh", "-c", "echo out; echo err >&2; exit 3"},
                                   (dir / "done.log").string(), std::chrono::seconds(10));
  EXPECT_EQ(done.status, 3);
  EXPECT_EQ(done.output, "out\nerr\n");
  const ProgramRun slow = RunToEnd({"/bin/sleep", "30"}, (dir / "slow.log").string(), std::chrono::milliseconds(200));
  EXPECT_EQ(slow.status, -1);
  EXPECT_TRUE(WaitForText(dir / "done.log", "err", 1));
  EXPECT_FALSE(WaitForText(dir / "done.log", "never said", 0.1));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace simpartner::test_support
