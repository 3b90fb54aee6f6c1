#include "aavio/recording/event_gaps.hpp"

#include <gtest/gtest.h>

namespace aavio::recording {
namespace {

TEST(EventGaps, ListsSilentStretchesPerCameraFrom50Ms) {
  const TimeNs t0 = 100 * kNsPerS;
  EventGaps gaps(t0);
  for (int k = 1; k <= 400; ++k) {
    const TimeNs t = t0 + k * 10 * kNsPerMs;
    const bool dark = k > 100 && k <= 150;       // 1.00 s to 1.50 s: neither camera
    const bool right_off = k > 200 && k <= 300;  // 2.00 s to 3.00 s: the right one
    const bool blip = k == 350;                  // one silent tick: not a gap
    gaps.Add(t, dark || blip ? 0 : 1000, dark || right_off ? 0 : 900);
  }
  gaps.Add(t0 + 401 * 10 * kNsPerMs, -1, 0);  // uncounted left; the right silent to the end
  gaps.Add(t0 + 420 * 10 * kNsPerMs, -1, 0);
  gaps.Finish(t0 + 420 * 10 * kNsPerMs);
  const nlohmann::json j = gaps.Json();
  ASSERT_EQ(j["left"].size(), 1u);
  EXPECT_NEAR(j["left"][0][0].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(j["left"][0][1].get<double>(), 1.51, 1e-9);
  ASSERT_EQ(j["right"].size(), 3u);
  EXPECT_NEAR(j["right"][1][0].get<double>(), 2.0, 1e-9);
  EXPECT_NEAR(j["right"][1][1].get<double>(), 3.01, 1e-9);
  EXPECT_NEAR(j["right"][2][0].get<double>(), 4.0, 1e-9);
  EXPECT_NEAR(j["right"][2][1].get<double>(), 4.2, 1e-9);
}

}  // namespace
}  // namespace aavio::recording
