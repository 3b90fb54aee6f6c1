#include "aavio/events/edge_sampler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <set>

#include "aavio/events/test_events.hpp"

namespace aavio::events {
namespace {

// An AA map over a 4×3 grid of a 64×48 sensor from random clustered events.
AaMap RandomAaMap(std::uint64_t seed, int events = 6000) {
  AdaptiveAccumulationConfig config;
  config.grid_cols = 4;
  config.grid_rows = 3;
  config.contrast_threshold = 1e9;  // never close: keep the whole window
  std::vector<Event> all = testing::RandomEvents(events, 64, 48, 0, 10 * kNsPerMs, seed);
  // Block 0 much busier than the others.
  const std::vector<Event> extra =
      testing::RandomEvents(events, 16, 16, 0, 10 * kNsPerMs, seed + 1);
  all.insert(all.end(), extra.begin(), extra.end());
  std::stable_sort(all.begin(), all.end(),
                   [](const Event& a, const Event& b) { return a.t_ns < b.t_ns; });
  AaMap map;
  AdaptiveAccumulator(64, 48, config).Build(all, 10 * kNsPerMs, &map);
  return map;
}

EdgeSamplingConfig Budget(int points) {
  EdgeSamplingConfig config;
  config.num_points = points;
  config.grid_cols = 4;
  config.grid_rows = 3;
  return config;
}

TEST(BlockQuotas, ProportionalCappedAndRedistributed) {
  EdgeSamplingConfig config = Budget(100);
  // 75 in proportion to {100, 50, 50, 0, 4}, capped at half; the rest evenly where room is left.
  const std::vector<int> quota = BlockQuotas({100, 50, 50, 0, 4}, config);
  EXPECT_EQ(std::accumulate(quota.begin(), quota.end(), 0), 100);
  EXPECT_LE(quota[0], 50);
  EXPECT_LE(quota[1], 25);
  EXPECT_EQ(quota[3], 0);
  EXPECT_LE(quota[4], 2);
  EXPECT_GE(quota[0], quota[1]);
  // More budget than half of everything: every block at its cap.
  config.num_points = 1000;
  EXPECT_EQ(BlockQuotas({100, 50, 50, 0, 4}, config), (std::vector<int>{50, 25, 25, 0, 2}));
  // Nothing to take.
  EXPECT_EQ(BlockQuotas({0, 0}, config), (std::vector<int>{0, 0}));
}

TEST(SampleAaMap, MeetsBudgetAndQuotasWithTheHighestCounts) {
  const AaMap map = RandomAaMap(1);
  const geometry::RectificationMaps maps = testing::IdentityMaps(64, 48);
  const EdgeSamplingConfig config = Budget(800);
  const std::vector<EdgeSample> samples = SampleAaMap(map, maps, config, 42);
  EXPECT_EQ(samples.size(), 800u);
  std::vector<int> sizes;
  for (const AaBlock& block : map.blocks)
    sizes.push_back(static_cast<int>(block.active.size()));
  const std::vector<int> quota = BlockQuotas(sizes, config);
  const BlockGrid grid(64, 48, 4, 3);
  std::vector<int> taken(12, 0), lowest_taken(12, 256);
  std::set<int> pixels;
  for (const EdgeSample& s : samples) {
    const int b = grid.BlockOf(s.x, s.y);
    ++taken[b];
    lowest_taken[b] = std::min<int>(lowest_taken[b], s.count);
    EXPECT_EQ(s.count, map.counts.at<std::uint8_t>(s.y, s.x));
    EXPECT_FLOAT_EQ(s.u, s.x);
    EXPECT_TRUE(pixels.insert(s.y * 64 + s.x).second) << "a pixel sampled twice";
  }
  EXPECT_EQ(taken, quota);
  // Nothing left behind in a block has a higher count than what was taken there.
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (pixels.count(y * 64 + x)) continue;
      EXPECT_LE(map.counts.at<std::uint8_t>(y, x), lowest_taken[grid.BlockOf(x, y)]);
    }
  }
  EXPECT_GT(taken[0], taken[5]);  // the busy block gives more
}

TEST(SampleAaMap, DeterministicForASeedAndTiesVaryWithIt) {
  const AaMap map = RandomAaMap(2);
  const geometry::RectificationMaps maps = testing::IdentityMaps(64, 48);
  auto key = [](const std::vector<EdgeSample>& samples) {
    std::vector<int> k;
    for (const EdgeSample& s : samples)
      k.push_back(s.y * 64 + s.x);
    return k;
  };
  const auto a = key(SampleAaMap(map, maps, Budget(500), 7));
  EXPECT_EQ(a, key(SampleAaMap(map, maps, Budget(500), 7)));
  EXPECT_NE(a, key(SampleAaMap(map, maps, Budget(500), 8)));
}

// min_spacing_px: no two samples within 2 px while a block has candidates that keep the
// spacing; a pixel left behind with a higher count than one taken in its block was skipped for
// a sample next to it. With more budget than spaced candidates the quotas are still met.
TEST(SampleAaMap, SpacedSamplesKeepTheirDistanceAndStillMeetTheQuotas) {
  const AaMap map = RandomAaMap(4);
  const geometry::RectificationMaps maps = testing::IdentityMaps(64, 48);
  const BlockGrid grid(64, 48, 4, 3);
  std::vector<int> sizes;
  for (const AaBlock& block : map.blocks)
    sizes.push_back(static_cast<int>(block.active.size()));
  auto near = [](const EdgeSample& a, int x, int y, int r) {
    return std::abs(a.x - x) <= r && std::abs(a.y - y) <= r;
  };
  EdgeSamplingConfig config = Budget(60);
  config.min_spacing_px = 2;
  const std::vector<EdgeSample> spaced = SampleAaMap(map, maps, config, 5);
  ASSERT_EQ(spaced.size(), 60u);
  std::vector<int> taken(12, 0), lowest_taken(12, 256);
  for (std::size_t i = 0; i < spaced.size(); ++i) {
    ++taken[grid.BlockOf(spaced[i].x, spaced[i].y)];
    lowest_taken[grid.BlockOf(spaced[i].x, spaced[i].y)] =
        std::min<int>(lowest_taken[grid.BlockOf(spaced[i].x, spaced[i].y)], spaced[i].count);
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_FALSE(near(spaced[j], spaced[i].x, spaced[i].y, 2)) << i << " next to " << j;
  }
  EXPECT_EQ(taken, BlockQuotas(sizes, config));
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      if (map.counts.at<std::uint8_t>(y, x) <= lowest_taken[grid.BlockOf(x, y)]) continue;
      EXPECT_TRUE(std::any_of(spaced.begin(), spaced.end(),
                              [&](const EdgeSample& s) { return near(s, x, y, 2); }))
          << "(" << x << ", " << y << ") skipped with nothing next to it";
    }
  }
  // 800 of the 64×48 pixels cannot all be 2 px apart: the quotas are filled, each pixel once.
  config.num_points = 800;
  const std::vector<EdgeSample> full = SampleAaMap(map, maps, config, 5);
  EXPECT_EQ(full.size(), 800u);
  std::set<int> pixels;
  for (const EdgeSample& s : full)
    EXPECT_TRUE(pixels.insert(s.y * 64 + s.x).second) << "a pixel sampled twice";
  std::vector<int> full_taken(12, 0);
  for (const EdgeSample& s : full)
    ++full_taken[grid.BlockOf(s.x, s.y)];
  EXPECT_EQ(full_taken, BlockQuotas(sizes, config));
  // Deterministic for a seed.
  const std::vector<EdgeSample> again = SampleAaMap(map, maps, config, 5);
  ASSERT_EQ(again.size(), full.size());
  for (std::size_t i = 0; i < full.size(); ++i)
    EXPECT_TRUE(again[i].x == full[i].x && again[i].y == full[i].y);
}

TEST(SampleAaMap, SkipsPixelsOutsideTheValidRectifiedArea) {
  const AaMap map = RandomAaMap(3);
  geometry::RectificationMaps maps = testing::IdentityMaps(64, 48);
  maps.raw_valid.colRange(0, 32).setTo(0);  // left half maps outside the valid area
  maps.raw_valid.at<std::uint8_t>(40, 40) = 0;
  for (const EdgeSample& s : SampleAaMap(map, maps, Budget(5000), 1)) {
    EXPECT_GE(s.u, 31.5f);
    EXPECT_FALSE(s.x == 40 && s.y == 40);
  }
}

TEST(SelectNewestEvents, NewestWithinTheWindowUpToTheBudget) {
  const geometry::RectificationMaps maps = testing::IdentityMaps(64, 48);
  const std::vector<Event> events = testing::RandomEvents(3000, 64, 48, 0, 30 * kNsPerMs, 4);
  EdgeSamplingConfig config = Budget(100000);
  config.mode = SamplingMode::kNewestEvents;
  const TimeNs tick = 25 * kNsPerMs;
  const std::vector<EdgeSample> all = SelectNewestEvents(events, tick, maps, config);
  std::size_t expected = 0;
  for (const Event& e : events)
    expected += e.t_ns > tick - 10 * kNsPerMs && e.t_ns <= tick;
  EXPECT_EQ(all.size(), expected);
  config.num_points = 50;
  const std::vector<EdgeSample> newest = SelectNewestEvents(events, tick, maps, config);
  ASSERT_EQ(newest.size(), 50u);
  EXPECT_EQ(newest.front().x, all.front().x);  // the same newest-first order
  EXPECT_EQ(newest.back().y, all[49].y);
}

}  // namespace
}  // namespace aavio::events
