#include "aavio/common/time.hpp"

#include <gtest/gtest.h>

namespace aavio {
namespace {

TEST(Time, ParsesDecimalSecondsExactly) {
  // UNIX-epoch stamps carry 19 significant digits: a double would lose the last ones.
  EXPECT_EQ(*ParseSecondsToNs("1468940145.123456789"), 1468940145123456789LL);
  EXPECT_EQ(*ParseSecondsToNs("36470.774788442"), 36470774788442LL);
  EXPECT_EQ(*ParseSecondsToNs("12"), 12 * kNsPerS);
  EXPECT_EQ(*ParseSecondsToNs("0.5"), 500'000'000);
  EXPECT_EQ(*ParseSecondsToNs(".25"), 250'000'000);
  EXPECT_EQ(*ParseSecondsToNs("-1.5"), -1'500'000'000);
  EXPECT_EQ(*ParseSecondsToNs("+3."), 3 * kNsPerS);
}

TEST(Time, RoundsDigitsBeyondNanoseconds) {
  EXPECT_EQ(*ParseSecondsToNs("1.0000000014"), 1'000'000'001);
  EXPECT_EQ(*ParseSecondsToNs("1.0000000015"), 1'000'000'002);
}

TEST(Time, ParsesExponentNotation) {
  EXPECT_EQ(*ParseSecondsToNs("3.6e4"), 36'000 * kNsPerS);
  EXPECT_EQ(*ParseSecondsToNs("1E-3"), kNsPerMs);
}

TEST(Time, RejectsMalformed) {
  for (const char* bad : {"", "abc", "1.2.3", "12s", "-", "1e", "nan", "1e30"}) {
    Expected<TimeNs> t = ParseSecondsToNs(bad);
    EXPECT_FALSE(t.ok()) << bad;
    if (!t.ok()) {
      EXPECT_EQ(t.status().code(), StatusCode::kParseError);
    }
  }
}

TEST(Time, FormatsNineDecimalsAndRoundTrips) {
  EXPECT_EQ(FormatSecondsNs(36470774788442LL), "36470.774788442");
  EXPECT_EQ(FormatSecondsNs(0), "0.000000000");
  EXPECT_EQ(FormatSecondsNs(-1'500'000'000), "-1.500000000");
  EXPECT_EQ(FormatSecondsNs(-1), "-0.000000001");
  for (TimeNs t : {1468940145123456789LL, 1LL, -987654321012LL, 999'999'999LL}) {
    EXPECT_EQ(*ParseSecondsToNs(FormatSecondsNs(t)), t);
  }
}

TEST(Time, Conversions) {
  EXPECT_EQ(UsToNs(36470123457LL), 36470123457000LL);
  EXPECT_EQ(MsToNs(2.0), 2'000'000);
  EXPECT_EQ(SecondsToNs(0.01), 10'000'000);
  EXPECT_DOUBLE_EQ(NsToSeconds(1'500'000'000), 1.5);
  EXPECT_DOUBLE_EQ(NsToMs(2'500'000), 2.5);
}

TEST(Time, SaturatingAddClampsAtTheEndsOfTime) {
  constexpr TimeNs kMax = std::numeric_limits<TimeNs>::max();
  constexpr TimeNs kMin = std::numeric_limits<TimeNs>::min();
  EXPECT_EQ(SaturatingAdd(5, 7), 12);
  EXPECT_EQ(SaturatingAdd(kMax, kNsPerMs), kMax);
  EXPECT_EQ(SaturatingAdd(kMax - 3, 2), kMax - 1);
  EXPECT_EQ(SaturatingAdd(kMin, -1), kMin);
  EXPECT_EQ(SaturatingAdd(kMin, kMax), -1);
}

}  // namespace
}  // namespace aavio
