// RateLimitedLog (common/rate_limited_log.h) and the signature refusals of
// BadMessageCounter (common/bus_decode.h) built on it, on a clock the test
// moves by hand: no test waits for real time.
#include "simpartner/rate_limited_log.h"

#include <gtest/gtest.h>

#include "simpartner/bus_decode.h"

namespace simpartner {
namespace {

using std::chrono::milliseconds;
using Clock = RateLimitedLog::Clock;

class RateLimitedLogTest : public ::testing::Test {
 protected:
  Clock::time_point At(int ms) const { return t0_ + milliseconds(ms); }
  Clock::time_point t0_ = Clock::now();
};

TEST_F(RateLimitedLogTest, TheFirstAtOnceThenOnePerPeriodCountingTheRest) {
  RateLimitedLog log(milliseconds(1000));
  EXPECT_EQ(log.Pass("k", "a", At(0)), std::optional<std::string>("a"));
  EXPECT_EQ(log.Pass("k", "b", At(200)), std::nullopt);
  EXPECT_EQ(log.Pass("k", "c", At(999)), std::nullopt);
  EXPECT_EQ(log.Pass("k", "d", At(1000)),
            std::optional<std::string>("d (and 2 more like it since the last report)"));
  EXPECT_EQ(log.Pass("k", "e", At(1500)), std::nullopt);
  EXPECT_EQ(log.Pass("k", "f", At(5000)),
            std::optional<std::string>("f (and 1 more like it since the last report)"));
  EXPECT_EQ(log.Pass("k", "g", At(6000)), std::optional<std::string>("g"));
}

TEST_F(RateLimitedLogTest, EachKeyHasItsOwnLimitAndZeroSaysEverything) {
  RateLimitedLog log(milliseconds(1000), "more refused");
  EXPECT_TRUE(log.Pass("SIM_STATE", "s", At(0)));
  EXPECT_TRUE(log.Pass("SIM_MODEL", "m", At(10)));
  EXPECT_FALSE(log.Pass("SIM_STATE", "s", At(20)));
  EXPECT_EQ(log.Pass("SIM_STATE", "s", At(1000)),
            std::optional<std::string>("s (and 1 more refused since the last report)"));
  RateLimitedLog every(Clock::duration::zero());
  for (int k = 0; k < 5; ++k) EXPECT_EQ(every.Pass("k", "x", At(0)), std::optional<std::string>("x"));
}

// A flood of refused signed messages on several channels: every one
// counted, one line a second for all of them, naming the newest with the
// number refused since the last line.
TEST_F(RateLimitedLogTest, SignatureRefusalsAreCountedAndNamedOnceASecond) {
  BadMessageCounter counter;
  const std::string command = "SIM_COMMAND: 140 bytes refused: replayed: timestamp 5";
  const std::string control = "SIM_CONTROL: 72 bytes refused: no signature";
  int lines = 0;
  for (int k = 0; k < 1000; ++k) {  // 1000 in 0.5 s
    const bool even = k % 2 == 0;
    lines += counter
                 .CountSignatureRefusal(even ? "SIM_COMMAND" : "SIM_CONTROL",
                                        even ? command : control, At(k / 2))
                 .has_value();
  }
  EXPECT_EQ(lines, 1);
  EXPECT_EQ(counter.total(), 1000u);
  EXPECT_EQ(counter.count("SIM_COMMAND"), 500u);
  EXPECT_EQ(counter.count("SIM_CONTROL"), 500u);
  EXPECT_EQ(counter.Summary(), "SIM_COMMAND 500, SIM_CONTROL 500");
  EXPECT_EQ(counter.CountSignatureRefusal("SIM_CONTROL", control, At(999)), std::nullopt);
  EXPECT_EQ(counter.CountSignatureRefusal("SIM_CONTROL", control, At(1000)),
            std::optional<std::string>(control +
                                       " (and 1000 more refused since the last report)"));
}

}  // namespace
}  // namespace simpartner
