// Signed bus messages (common/bus_signing.h): what verifies, and every way
// a message without the key, altered, replayed or stale is refused.
#include "simpartner/bus_signing.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "../support/test_dir.h"
#include "simpartner/sender.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

BusSigning::Key KeyOf(uint8_t fill) {
  BusSigning::Key key;
  key.fill(fill);
  return key;
}

const std::vector<uint8_t> kMessage = {1, 2, 3, 4, 5, 6, 7, 8, 9};

TEST(BusSigning, ASignedMessageOpensToItselfOnceAndOnlyOnItsChannel) {
  BusSigning sender(KeyOf(7)), reader(KeyOf(7));
  const std::vector<uint8_t> signed_bytes =
      sender.Sign("SIM_COMMAND", kMessage.data(), kMessage.size());
  ASSERT_EQ(signed_bytes.size(), kMessage.size() + kSignatureBytes);
  EXPECT_TRUE(std::equal(kMessage.begin(), kMessage.end(), signed_bytes.begin()));
  const int64_t now = WallMicros();
  BusSigning::Opened opened =
      reader.Open("SIM_COMMAND", signed_bytes.data(), signed_bytes.size(), now);
  EXPECT_EQ(opened.refusal, "");
  EXPECT_EQ(opened.size, kMessage.size());
  // The same datagram again: a replay.
  opened = reader.Open("SIM_COMMAND", signed_bytes.data(), signed_bytes.size(), now);
  EXPECT_EQ(opened.refusal.rfind("replayed: ", 0), 0u) << opened.refusal;
  // On another channel (a command replayed as a control): its tag is wrong.
  BusSigning other_reader(KeyOf(7));
  opened = other_reader.Open("SIM_CONTROL", signed_bytes.data(), signed_bytes.size(), now);
  EXPECT_EQ(opened.refusal.rfind("wrong signature", 0), 0u) << opened.refusal;
  // The next one of the sender verifies.
  const auto next = sender.Sign("SIM_COMMAND", kMessage.data(), kMessage.size());
  EXPECT_EQ(reader.Open("SIM_COMMAND", next.data(), next.size(), now).refusal, "");
}

TEST(BusSigning, AnotherKeyAnAlteredByteNoSignatureOrAnOldStreamAreRefused) {
  BusSigning sender(KeyOf(7)), forger(KeyOf(8)), reader(KeyOf(7));
  const int64_t now = WallMicros();
  const auto forged = forger.Sign("SIM_STATE", kMessage.data(), kMessage.size());
  auto refusal = [&](const std::vector<uint8_t>& bytes) {
    return reader.Open("SIM_STATE", bytes.data(), bytes.size(), now).refusal;
  };
  EXPECT_EQ(refusal(forged).rfind("wrong signature", 0), 0u);
  auto altered = sender.Sign("SIM_STATE", kMessage.data(), kMessage.size());
  altered[3] ^= 1;
  EXPECT_EQ(refusal(altered).rfind("wrong signature", 0), 0u);
  EXPECT_EQ(refusal(kMessage).rfind("no signature", 0), 0u);
  // A stream recorded two minutes ago (lcm-logger, then lcm-logplayer).
  const auto recorded = sender.Sign("SIM_STATE", kMessage.data(), kMessage.size());
  BusSigning later_reader(KeyOf(7));
  const auto opened =
      later_reader.Open("SIM_STATE", recorded.data(), recorded.size(), now + 120000000);
  EXPECT_EQ(opened.refusal.rfind("stale: ", 0), 0u) << opened.refusal;
}

// A time [us] the replay-window tests date their messages at.
constexpr int64_t kT = 1700000000000000;

// kMessage signed by `sender` for "SIM_STATE", dated `when`.
std::vector<uint8_t> SignedAt(BusSigning* sender, int64_t when) {
  return sender->Sign("SIM_STATE", kMessage.data(), kMessage.size(), when);
}

// A reader of "SIM_STATE" at `now`: each call opens `bytes`, gives the refusal.
auto OpenerAt(BusSigning* reader, int64_t now) {
  return [reader, now](const std::vector<uint8_t>& bytes) {
    return reader->Open("SIM_STATE", bytes.data(), bytes.size(), now).refusal;
  };
}

// UDP multicast may deliver a link's messages out of order: one overtaken
// by a later one of its sender is still accepted, once.
TEST(BusSigning, AMessageOvertakenByALaterOneIsAcceptedOnce) {
  BusSigning sender(KeyOf(7)), reader(KeyOf(7));
  const auto first = SignedAt(&sender, kT);
  const auto second = SignedAt(&sender, kT + 300);
  const auto open = OpenerAt(&reader, kT + 1000);
  EXPECT_EQ(open(second), "");
  EXPECT_EQ(open(first), "");  // 300 us late
  EXPECT_EQ(open(first), "replayed: timestamp 1700000000000000 us was accepted from its sender "
                         "already");
  EXPECT_EQ(open(second), "replayed: timestamp 1700000000000300 us was accepted from its sender "
                          "already");
}

// Older than the window, by time (1 s) or by count (64 accepted since):
// refused, though never read before.
TEST(BusSigning, AMessageOlderThanTheReplayWindowIsRefused) {
  BusSigning sender(KeyOf(7)), reader(KeyOf(7));
  const auto early = SignedAt(&sender, kT);
  const auto late = SignedAt(&sender, kT + 1500000);
  const auto open = OpenerAt(&reader, kT + 1500000);
  EXPECT_EQ(open(late), "");
  EXPECT_EQ(open(early), "replayed: timestamp 1700000000000000 us is 1500000 us before the "
                         "newest of its sender, older than its replay window (the last 64 "
                         "messages within 1000000 us)");

  BusSigning stream_sender(KeyOf(7)), stream_reader(KeyOf(7));
  const auto held_back = SignedAt(&stream_sender, kT);
  const auto read = OpenerAt(&stream_reader, kT);
  for (int k = 1; k <= 65; ++k)  // 1 us apart
    ASSERT_EQ(read(SignedAt(&stream_sender, kT + k)), "");
  EXPECT_EQ(read(held_back).rfind("replayed: timestamp 1700000000000000 us is 65 us before", 0),
            0u)
      << read(held_back);
}

TEST(BusSigning, AReaderWithoutAKeyDropsTheSignatureUnread) {
  BusSigning sender(KeyOf(7));
  const auto signed_bytes = sender.Sign("SIM_STATE", kMessage.data(), kMessage.size());
  EXPECT_EQ(UnsignedSize(signed_bytes.data(), signed_bytes.size()), kMessage.size());
  EXPECT_EQ(UnsignedSize(kMessage.data(), kMessage.size()), kMessage.size());
}

class BusKeyFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_bus_key_", 40); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& text, mode_t mode) {
    const fs::path path = dir_ / "bus.key";
    std::ofstream(path, std::ios::binary) << text;
    ::chmod(path.c_str(), mode);
    return path.string();
  }
  static std::string Refusal(const std::string& path) {
    try {
      BusSigning::LoadKey(path);
      return "loaded";
    } catch (const BusKeyError& e) {
      return e.what();
    }
  }
  fs::path dir_;
};

TEST_F(BusKeyFileTest, ThirtyTwoBytesOrSixtyFourHexDigitsInAPrivateFile) {
  EXPECT_EQ(BusSigning::LoadKey(Write(std::string(32, 'k'), 0600)), KeyOf('k'));
  EXPECT_EQ(BusSigning::LoadKey(Write(std::string(64, 'a') + "\n", 0600)), KeyOf(0xaa));
  const std::string open = Write(std::string(32, 'k'), 0644);
  EXPECT_EQ(Refusal(open), open + ": bus key file readable by others (mode 0644): chmod 600 it");
  const std::string short_key = Write("secret\n", 0600);
  EXPECT_NE(Refusal(short_key).find(
                "a bus key file holds 32 bytes or 64 hex digits, this one 6 bytes"),
            std::string::npos);
  EXPECT_NE(Refusal((dir_ / "none").string()).find("cannot read the bus key file"),
            std::string::npos);
}

// Which key a program signs with (ChooseBusKeyFile), in an environment the
// test sets: SIMPARTNER_BUS_KEY and where the user's key lives.
class BusKeyChoiceTest : public BusKeyFileTest {
 protected:
  void SetUp() override {
    BusKeyFileTest::SetUp();
    for (const char* name : {kBusKeyVariable, "XDG_CONFIG_HOME", "HOME"})
      if (const char* value = std::getenv(name)) saved_[name] = value;
    ::unsetenv(kBusKeyVariable);
    ::setenv("XDG_CONFIG_HOME", (dir_ / "config").c_str(), 1);
  }
  void TearDown() override {
    for (const char* name : {kBusKeyVariable, "XDG_CONFIG_HOME", "HOME"}) {
      if (saved_.count(name)) ::setenv(name, saved_[name].c_str(), 1);
      else ::unsetenv(name);
    }
    BusKeyFileTest::TearDown();
  }
  // The key file chosen, and what was said.
  std::pair<std::string, std::vector<std::string>> Choose() {
    std::vector<std::string> said;
    const std::string path =
        ChooseBusKeyFile([&said](const std::string& line) { said.push_back(line); });
    return {path, said};
  }
  std::map<std::string, std::string> saved_;
};

TEST_F(BusKeyChoiceTest, NothingSetMakesTheUsersKeyOnceAndSaysWhere) {
  const std::string user_key = (dir_ / "config" / "simpartner" / "bus.key").string();
  const auto [path, said] = Choose();
  EXPECT_EQ(path, user_key);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].rfind("made the bus key " + user_key + " (mode 0600): every SimPartner "
                          "program of this user signs with it",
                          0),
            0u)
      << said[0];
  struct stat info {};
  ASSERT_EQ(::stat(user_key.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  ASSERT_EQ(::stat((dir_ / "config" / "simpartner").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0077, 0u);
  const BusSigning::Key key = BusSigning::LoadKey(user_key);
  EXPECT_NE(key, KeyOf(0));
  const auto [again, said_again] = Choose();  // found, not made again
  EXPECT_EQ(again, user_key);
  EXPECT_TRUE(said_again.empty());
  EXPECT_EQ(BusSigning::LoadKey(user_key), key);
  // An empty variable is no choice either.
  ::setenv(kBusKeyVariable, "", 1);
  EXPECT_EQ(Choose().first, user_key);
}

TEST_F(BusKeyChoiceTest, NoneIsUnsignedAndSaidAKeyFileIsTakenAsItIs) {
  ::setenv(kBusKeyVariable, kNoBusKey, 1);
  const auto [none, said] = Choose();
  EXPECT_EQ(none, "");
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].rfind("the bus is unsigned (SIMPARTNER_BUS_KEY=none): any process that can "
                          "reach it can command the robot",
                          0),
            0u)
      << said[0];
  EXPECT_FALSE(BusSigning::FromEnvironment({}).has_value());
  const std::string file = Write(std::string(64, 'b'), 0600);
  ::setenv(kBusKeyVariable, file.c_str(), 1);
  const auto [chosen, quiet] = Choose();
  EXPECT_EQ(chosen, file);
  EXPECT_TRUE(quiet.empty());
  EXPECT_FALSE(fs::exists(dir_ / "config")) << "the user's key was made though a file was named";
  const std::optional<BusSigning> signing = BusSigning::FromEnvironment({});
  ASSERT_TRUE(signing.has_value());
  EXPECT_EQ(signing->key_file(), file);
}

// The XDG base directory rule: a relative XDG_CONFIG_HOME is ignored for
// ~/.config; with no home either, the error says what to set.
TEST_F(BusKeyChoiceTest, WithoutAnAbsoluteConfigDirectoryHomeIsUsedOrTheErrorSaysWhatToSet) {
  ::setenv("XDG_CONFIG_HOME", "relative/config", 1);
  ::setenv("HOME", (dir_ / "home").c_str(), 1);
  EXPECT_EQ(Choose().first, (dir_ / "home" / ".config" / "simpartner" / "bus.key").string());
  ::unsetenv("XDG_CONFIG_HOME");
  ::unsetenv("HOME");
  try {
    Choose();
    ADD_FAILURE() << "no error without a home";
  } catch (const BusKeyError& e) {
    EXPECT_NE(std::string(e.what()).find("set SIMPARTNER_BUS_KEY to a key file"), std::string::npos)
        << e.what();
  }
}

// A config directory that cannot be made (here a file stands where it
// would be: root may write anywhere else): the error names it and the
// way around.
TEST_F(BusKeyChoiceTest, WhereTheKeyCannotBeMadeTheErrorNamesThePathAndTheWayAround) {
  std::ofstream(dir_ / "config") << "a file, not a directory\n";
  try {
    Choose();
    ADD_FAILURE() << "a key was made under a file";
  } catch (const BusKeyError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir_ / "config" / "simpartner").string() +
                  ": cannot make the bus key's directory: Not a directory (or set "
                  "SIMPARTNER_BUS_KEY to a key file: docs/security.md)");
  }
}

// The programs of a run start at once: of 16 threads making the same key,
// exactly one makes it, every one then reads that key, and nothing is
// left beside it.
TEST_F(BusKeyChoiceTest, ProgramsStartingAtOnceShareOneKey) {
  const std::string path = (dir_ / "config" / "simpartner" / "bus.key").string();
  std::vector<int> made(16, 0);
  std::vector<BusSigning::Key> keys(made.size());
  std::vector<std::thread> threads;
  for (size_t i = 0; i < made.size(); ++i)
    threads.emplace_back([&, i] {
      made[i] = MakeBusKeyIfMissing(path) ? 1 : 0;
      keys[i] = BusSigning::LoadKey(path);
    });
  for (std::thread& t : threads) t.join();
  int makers = 0;
  for (const int m : made) makers += m;
  EXPECT_EQ(makers, 1);
  for (const BusSigning::Key& key : keys) EXPECT_EQ(key, keys[0]);
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "config" / "simpartner")) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "bus.key");
  }
  EXPECT_EQ(files, 1u);
}

// What a reader heard tells why it may hear no answer: a signed bus and no
// key, an unsigned bus and a key, or another key; a bus that matches says
// nothing.
TEST(SigningMismatch, NamesASignedBusWithoutAKeyAnUnsignedOneWithAKeyAndAnotherKey) {
  const int64_t now = WallMicros();
  BusSigning sim(KeyOf(7));
  const auto signed_bytes = sim.Sign("SIM_STATUS", kMessage.data(), kMessage.size(), now);
  auto heard = [&](BusSigning* reader, const std::vector<uint8_t>& bytes, SigningMismatch* mismatch) {
    mismatch->Note(reader != nullptr, bytes.data(), bytes.size(),
                   OpenMessage(reader, "SIM_STATUS", bytes.data(), bytes.size()));
  };

  SigningMismatch no_key;
  heard(nullptr, kMessage, &no_key);
  EXPECT_EQ(no_key.Hint(), "") << "an unsigned bus, no key: they match";
  heard(nullptr, signed_bytes, &no_key);
  EXPECT_NE(no_key.Hint().find("this bus is signed (1 messages heard carry a signature) and this "
                               "program has no key"),
            std::string::npos)
      << no_key.Hint();
  EXPECT_NE(no_key.Hint().find("set SIMPARTNER_BUS_KEY"), std::string::npos) << no_key.Hint();

  BusSigning same_key(KeyOf(7)), other_key(KeyOf(9));
  SigningMismatch right, wrong, unsigned_bus;
  heard(&same_key, signed_bytes, &right);
  EXPECT_EQ(right.Hint(), "");
  heard(&other_key, signed_bytes, &wrong);
  EXPECT_NE(wrong.Hint().find("1 messages heard did not verify with this program's key, and none "
                              "did: the bus uses another key (copy the sim's key file: "
                              "docs/several-machines.md) (SIMPARTNER_BUS_KEY; docs/security.md)"),
            std::string::npos)
      << wrong.Hint();
  heard(&same_key, kMessage, &unsigned_bus);
  EXPECT_NE(unsigned_bus.Hint().find("messages heard are unsigned and this program has a key"),
            std::string::npos)
      << unsigned_bus.Hint();
  // Unsigned forgeries on a signed bus whose own messages verify: the bus
  // matches; the forgeries are counted elsewhere.
  heard(&same_key, kMessage, &right);
  EXPECT_EQ(right.Hint(), "");
}

}  // namespace
}  // namespace simpartner
