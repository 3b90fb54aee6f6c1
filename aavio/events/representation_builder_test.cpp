#include "aavio/events/representation_builder.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "aavio/events/test_events.hpp"

namespace aavio::events {
namespace {

constexpr int kW = 64, kH = 48;

geometry::StereoRectification Identity() {
  return {testing::IdentityMaps(kW, kH), testing::IdentityMaps(kW, kH)};
}

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

struct Streams {
  std::vector<Event> left = testing::RandomEvents(20000, kW, kH, 0, 100 * kNsPerMs, 11);
  std::vector<Event> right = testing::RandomEvents(20000, kW, kH, 0, 100 * kNsPerMs, 12);
};

TEST(RepresentationBuilder, ObservationMatchesItsParts) {
  const Streams s;
  RepresentationConfig config;
  config.adaptive_accumulation.grid_cols = config.edge_sampling.grid_cols = 4;
  config.adaptive_accumulation.grid_rows = config.edge_sampling.grid_rows = 3;
  config.edge_sampling.num_points = 300;
  RepresentationBuilder builder(Identity(), kW, kH, config, 0);
  ASSERT_TRUE(builder.AddEvents(Camera::kLeft, s.left).ok());
  ASSERT_TRUE(builder.AddEvents(Camera::kRight, s.right).ok());
  Observation obs;
  ASSERT_TRUE(builder.Build(60 * kNsPerMs, &obs).ok());
  // TS: the definition, then the 3×3 median (identity rectification).
  cv::Mat expected;
  cv::medianBlur(BruteForceTimeSurface(s.right, kW, kH, 60 * kNsPerMs, 30.0), expected, 3);
  cv::Mat diff;
  cv::absdiff(obs.ts_right, expected, diff);
  EXPECT_LE(cv::countNonZero(diff), kW * kH / 200);  // ±1 level where rounding is a tie
  // AA: the accumulator's map over the same events.
  AaMap aa;
  AdaptiveAccumulator(kW, kH, config.adaptive_accumulation).Build(s.left, 60 * kNsPerMs, &aa);
  EXPECT_TRUE(Same(obs.aa_counts_raw, aa.counts));
  EXPECT_EQ(cv::countNonZero(obs.aa_map), cv::countNonZero(aa.counts));
  EXPECT_EQ(obs.samples.size(), 300u);
  EXPECT_EQ(obs.grad_u.type(), CV_32FC1);
  EXPECT_EQ(obs.negative_ts_left.type(), CV_8UC1);
}

// With map_count_gain the AA map temporal stereo matches holds gain · count (saturating at 255)
// instead of 255 wherever an event was accumulated (identity rectification: pixel for pixel).
TEST(RepresentationBuilder, AaMapScalesCountsWhenAsked) {
  const Streams s;
  RepresentationConfig config;
  config.adaptive_accumulation.grid_cols = config.edge_sampling.grid_cols = 4;
  config.adaptive_accumulation.grid_rows = config.edge_sampling.grid_rows = 3;
  auto build = [&](int gain) {
    config.adaptive_accumulation.map_count_gain = gain;
    RepresentationBuilder builder(Identity(), kW, kH, config, 0);
    EXPECT_TRUE(builder.AddEvents(Camera::kLeft, s.left).ok());
    EXPECT_TRUE(builder.AddEvents(Camera::kRight, s.right).ok());
    Observation obs;
    EXPECT_TRUE(builder.Build(60 * kNsPerMs, &obs).ok());
    return obs;
  };
  const Observation binary = build(0), scaled = build(64);
  ASSERT_TRUE(Same(binary.aa_counts_raw, scaled.aa_counts_raw));
  int ones = 0, many = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const int count = scaled.aa_counts_raw.at<std::uint8_t>(y, x);
      EXPECT_EQ(binary.aa_map.at<std::uint8_t>(y, x), count > 0 ? 255 : 0);
      EXPECT_EQ(scaled.aa_map.at<std::uint8_t>(y, x), std::min(255, 64 * count));
      ones += count == 1 ? 1 : 0;
      many += count >= 4 ? 1 : 0;
    }
  }
  EXPECT_GT(ones, 100);  // both levels occur, so the comparison means something
  EXPECT_GT(many, 0);
  config.adaptive_accumulation.map_count_gain = 300;
  EXPECT_FALSE(config.adaptive_accumulation.Validate().ok());
}

TEST(RepresentationBuilder, EventsAfterTheTickWaitForTheNextOne) {
  const Streams s;
  RepresentationConfig config;
  RepresentationBuilder all(Identity(), kW, kH, config, 0), upto(Identity(), kW, kH, config, 0);
  std::vector<Event> early_l, early_r;
  for (const Event& e : s.left)
    if (e.t_ns <= 50 * kNsPerMs) early_l.push_back(e);
  for (const Event& e : s.right)
    if (e.t_ns <= 50 * kNsPerMs) early_r.push_back(e);
  ASSERT_TRUE(all.AddEvents(Camera::kLeft, s.left).ok());
  ASSERT_TRUE(all.AddEvents(Camera::kRight, s.right).ok());
  ASSERT_TRUE(upto.AddEvents(Camera::kLeft, early_l).ok());
  ASSERT_TRUE(upto.AddEvents(Camera::kRight, early_r).ok());
  Observation a, b;
  ASSERT_TRUE(all.Build(50 * kNsPerMs, &a).ok());
  ASSERT_TRUE(upto.Build(50 * kNsPerMs, &b).ok());
  EXPECT_TRUE(Same(a.ts_left, b.ts_left));
  EXPECT_TRUE(Same(a.ts_right, b.ts_right));
  EXPECT_TRUE(Same(a.aa_counts_raw, b.aa_counts_raw));
  // And the next tick sees them.
  ASSERT_TRUE(all.Build(100 * kNsPerMs, &a).ok());
  EXPECT_GT(a.aa_window_events, 0);
}

// Tracking ticks skip the right TS, the AA map and the samples; a mapping tick after them gets
// exactly what a builder drawing everything at every tick gets.
TEST(RepresentationBuilder, SkippedTicksLeaveTheNextMappingTickUnchanged) {
  const Streams s;
  RepresentationConfig config;
  config.edge_sampling.num_points = 200;
  RepresentationBuilder every(Identity(), kW, kH, config, 0), some(Identity(), kW, kH, config, 0);
  for (RepresentationBuilder* b : {&every, &some}) {
    ASSERT_TRUE(b->AddEvents(Camera::kLeft, s.left).ok());
    ASSERT_TRUE(b->AddEvents(Camera::kRight, s.right).ok());
  }
  int k = 0;
  for (TimeNs t = 10 * kNsPerMs; t <= 100 * kNsPerMs; t += 10 * kNsPerMs, ++k) {
    const bool maps = k % 3 == 2;
    Observation a, b;
    ASSERT_TRUE(every.Build(t, &a).ok());
    ASSERT_TRUE(some.Build(t, &b, {.right_ts = maps, .edges = maps}).ok());
    EXPECT_TRUE(Same(a.ts_left, b.ts_left) && Same(a.grad_u, b.grad_u));
    EXPECT_TRUE(a.timings.edges);
    EXPECT_EQ(b.timings.edges, maps);
    if (!maps) {
      EXPECT_TRUE(b.ts_right.empty() && b.aa_map.empty() && b.samples.empty());
      continue;
    }
    EXPECT_TRUE(Same(a.ts_right, b.ts_right) && Same(a.aa_map, b.aa_map));
    EXPECT_GT(b.samples.size(), 0u);
    ASSERT_EQ(a.samples.size(), b.samples.size());
    for (std::size_t i = 0; i < a.samples.size(); ++i) {
      EXPECT_EQ(a.samples[i].x, b.samples[i].x);
      EXPECT_EQ(a.samples[i].y, b.samples[i].y);
    }
  }
}

TEST(RepresentationBuilder, SameEventsSameObservationsTickAfterTick) {
  const Streams s;
  RepresentationConfig config;
  config.edge_sampling.num_points = 200;
  RepresentationBuilder one(Identity(), kW, kH, config, 0), two(Identity(), kW, kH, config, 0);
  for (RepresentationBuilder* b : {&one, &two}) {
    ASSERT_TRUE(b->AddEvents(Camera::kLeft, s.left).ok());
    ASSERT_TRUE(b->AddEvents(Camera::kRight, s.right).ok());
  }
  for (TimeNs t = 10 * kNsPerMs; t <= 100 * kNsPerMs; t += 10 * kNsPerMs) {
    Observation a, b;
    ASSERT_TRUE(one.Build(t, &a).ok());
    ASSERT_TRUE(two.Build(t, &b).ok());
    EXPECT_TRUE(Same(a.ts_left, b.ts_left) && Same(a.grad_v, b.grad_v) && Same(a.aa_map, b.aa_map));
    ASSERT_EQ(a.samples.size(), b.samples.size());
    for (std::size_t i = 0; i < a.samples.size(); ++i) {
      EXPECT_EQ(a.samples[i].x, b.samples[i].x);
      EXPECT_EQ(a.samples[i].y, b.samples[i].y);
    }
  }
}

TEST(RepresentationBuilder, RefusesDisorder) {
  RepresentationBuilder builder(Identity(), kW, kH, {}, 0);
  const std::vector<Event> backwards = {{20, 1, 1, 1}, {10, 1, 1, 1}};
  EXPECT_NE(builder.AddEvents(Camera::kRight, backwards)
                .message()
                .find("right events are not in time order"),
            std::string::npos);
  Observation obs;
  ASSERT_TRUE(builder.Build(10 * kNsPerMs, &obs).ok());
  EXPECT_FALSE(builder.Build(10 * kNsPerMs, &obs).ok());
  const std::vector<Event> stale = {{5 * kNsPerMs, 1, 1, 1}};
  EXPECT_NE(builder.AddEvents(Camera::kLeft, stale).message().find("after the tick"),
            std::string::npos);
}

}  // namespace
}  // namespace aavio::events
