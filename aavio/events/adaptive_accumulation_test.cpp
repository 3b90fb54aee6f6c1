#include "aavio/events/adaptive_accumulation.hpp"

#include <gtest/gtest.h>

#include "aavio/events/test_events.hpp"

namespace aavio::events {
namespace {

AdaptiveAccumulationConfig OneBlock() {
  AdaptiveAccumulationConfig config;
  config.grid_cols = config.grid_rows = 1;
  config.check_interval_ms = 1.0;
  config.window_ms = 10.0;
  return config;
}

Event At(double ms_before_tick, int x, int y, TimeNs tick) {
  return {tick - static_cast<TimeNs>(ms_before_tick * 1e6), static_cast<std::uint16_t>(x),
          static_cast<std::uint16_t>(y), 1};
}

std::vector<Event> Sorted(std::vector<Event> events) {
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.t_ns < b.t_ns; });
  return events;
}

TEST(BlockGrid, TilesEverySensorSize) {
  const BlockGrid dsec(640, 480, 8, 6);
  EXPECT_EQ(dsec.BlockOf(79, 79), 0);
  EXPECT_EQ(dsec.BlockOf(80, 0), 1);
  EXPECT_EQ(dsec.BlockOf(639, 479), 47);
  const BlockGrid mvsec(346, 260, 8, 6);  // 43.25 px blocks: every block gets 43 or 44 columns
  int columns_of_block0 = 0;
  for (int x = 0; x < 346; ++x)
    columns_of_block0 += mvsec.BlockOf(x, 0) == 0 ? 1 : 0;
  EXPECT_GE(columns_of_block0, 43);
  EXPECT_LE(columns_of_block0, 44);
  EXPECT_EQ(mvsec.BlockOf(345, 259), 47);
}

TEST(AdaptiveAccumulation, IncrementalContrastEqualsBruteForce) {
  const int w = 64, h = 48;
  const TimeNs tick = 10 * kNsPerMs;
  AdaptiveAccumulationConfig config;
  config.grid_cols = 4;
  config.grid_rows = 3;
  // Clustered events: a few hot pixels per block among uniform ones make contrasts of all sizes.
  std::vector<Event> events = testing::RandomEvents(4000, w, h, 0, tick, 5);
  const std::vector<Event> hot = testing::RandomEvents(2000, 8, 6, 0, tick, 6);
  for (Event e : hot) {
    e.x = static_cast<std::uint16_t>(e.x * 8);
    e.y = static_cast<std::uint16_t>(e.y * 8);
    events.push_back(e);
  }
  events = Sorted(events);
  {
    AdaptiveAccumulator accumulator(w, h, config);
    AaMap map;
    accumulator.Build(events, tick, &map);
    cv::Mat counts16;
    map.counts.convertTo(counts16, CV_16U);
    int closed = 0;
    for (int b = 0; b < 12; ++b) {
      const cv::Rect block((b % 4) * 16, (b / 4) * 16, 16, 16);
      EXPECT_NEAR(map.blocks[b].contrast, NonZeroVariance(counts16, block), 1e-9) << "block " << b;
      EXPECT_EQ(static_cast<int>(map.blocks[b].active.size()), cv::countNonZero(map.counts(block)));
      EXPECT_EQ(map.blocks[b].events, static_cast<int>(cv::sum(map.counts(block))[0]));
      closed += map.blocks[b].closed ? 1 : 0;
    }
    EXPECT_GT(closed, 0);
    EXPECT_LT(map.used_events, map.window_events);
  }
}

TEST(AdaptiveAccumulation, NewestFirstStopsAtTheFirstCheckWithContrast) {
  const TimeNs tick = 100 * kNsPerMs;
  // Within 1 ms of the tick: counts {3, 1} → variance 1 > β = 0.5. Older: single hits elsewhere.
  const std::vector<Event> events =
      Sorted({At(0.1, 1, 1, tick), At(0.2, 1, 1, tick), At(0.3, 1, 1, tick), At(0.4, 2, 2, tick),
              At(2.5, 5, 5, tick), At(6.0, 6, 6, tick)});
  AdaptiveAccumulator accumulator(10, 10, OneBlock());
  AaMap map;
  accumulator.Build(events, tick, &map);
  EXPECT_TRUE(map.blocks[0].closed);
  EXPECT_EQ(map.used_events, 4);
  EXPECT_EQ(map.counts.at<std::uint8_t>(1, 1), 3);
  EXPECT_EQ(map.counts.at<std::uint8_t>(5, 5), 0);
  EXPECT_DOUBLE_EQ(map.blocks[0].contrast, 1.0);
  EXPECT_EQ(map.window_events, 6);
}

TEST(AdaptiveAccumulation, UniformSingleHitsNeverCloseAndKeepTheWindow) {
  const TimeNs tick = 100 * kNsPerMs;
  std::vector<Event> events;
  for (int i = 0; i < 9; ++i)
    events.push_back(At(9.5 - i, i, i, tick));
  events.push_back(At(12.0, 9, 9, tick));  // outside the 10 ms window
  AdaptiveAccumulator accumulator(10, 10, OneBlock());
  AaMap map;
  accumulator.Build(Sorted(events), tick, &map);
  EXPECT_FALSE(map.blocks[0].closed);
  EXPECT_EQ(map.used_events, 9);
  EXPECT_EQ(map.window_events, 9);
  EXPECT_EQ(map.counts.at<std::uint8_t>(9, 9), 0);
  EXPECT_DOUBLE_EQ(map.blocks[0].contrast, 0.0);
}

TEST(AdaptiveAccumulation, NewestFirstFreezesTheNewestEdge) {
  const TimeNs tick = 100 * kNsPerMs;
  // The same contrasty pattern early (pixel 1,1) and late (pixel 8,8) in the window.
  const std::vector<Event> events =
      Sorted({At(9.9, 1, 1, tick), At(9.8, 1, 1, tick), At(9.7, 1, 1, tick), At(9.6, 2, 2, tick),
              At(0.4, 8, 8, tick), At(0.3, 8, 8, tick), At(0.2, 8, 8, tick), At(0.1, 7, 7, tick)});
  AaMap map;
  AdaptiveAccumulator(10, 10, OneBlock()).Build(events, tick, &map);
  EXPECT_EQ(map.counts.at<std::uint8_t>(1, 1), 0);
  EXPECT_EQ(map.counts.at<std::uint8_t>(8, 8), 3);
}

TEST(AdaptiveAccumulation, ReuseGivesTheSameMapAsAFreshAccumulator) {
  const std::vector<Event> a = testing::RandomEvents(5000, 40, 30, 0, 20 * kNsPerMs, 9);
  AdaptiveAccumulationConfig config;
  config.grid_cols = 4;
  config.grid_rows = 3;
  AdaptiveAccumulator reused(40, 30, config);
  AaMap first, second, fresh;
  reused.Build(a, 10 * kNsPerMs, &first);
  reused.Build(a, 20 * kNsPerMs, &second);
  AdaptiveAccumulator(40, 30, config).Build(a, 20 * kNsPerMs, &fresh);
  EXPECT_EQ(cv::countNonZero(second.counts != fresh.counts), 0);
  EXPECT_EQ(second.used_events, fresh.used_events);
}

}  // namespace
}  // namespace aavio::events
