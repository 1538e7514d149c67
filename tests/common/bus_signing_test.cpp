// Signed bus messages (common/bus_signing.h): what verifies, and every way
// a message without the key, altered, replayed or stale is refused.
#include "simpartner/bus_signing.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace simpartner
