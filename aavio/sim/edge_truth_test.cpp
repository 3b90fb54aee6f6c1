#include "aavio/sim/edge_truth.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "aavio/geometry/rectification.hpp"

namespace aavio::sim {
namespace {

SimulationWorld World(const char* preset, double duration_s) {
  SimulationRequest request;
  request.preset = preset;
  request.duration_s = duration_s;
  return *BuildSimulationWorld(request);
}

TEST(EdgeTruth, MarksTexturedAndOccludingEdgesOnly) {
  const SimulationWorld world = World("mini", 1.0);
  const TimeNs t = world.spline.t_begin_ns() + kNsPerS / 2;
  EdgeTruthConfig config;
  config.tolerance_px = 0;
  const cv::Mat edges = EdgeTruthMask(world, t, config);
  const double density = cv::countNonZero(edges) / static_cast<double>(edges.total());
  EXPECT_GT(density, 0.03);  // a textured room has edges …
  EXPECT_LT(density, 0.6);   // … but is not all edges
  config.tolerance_px = 1;
  EXPECT_GT(cv::countNonZero(EdgeTruthMask(world, t, config)), cv::countNonZero(edges));
}

TEST(EdgeTruth, ScoresSamplesAgainstTheMask) {
  cv::Mat edges(40, 80, CV_8UC1, cv::Scalar(0)), valid(40, 80, CV_8UC1, cv::Scalar(255));
  edges.col(10).setTo(255);  // 40 of 3200 pixels: density 1/80
  std::vector<events::EdgeSample> samples;
  for (std::uint16_t y = 0; y < 40; ++y)
    samples.push_back({10, y, 10.0f, static_cast<float>(y), 1});
  for (std::uint16_t y = 0; y < 40; ++y)
    samples.push_back({70, y, 70.0f, static_cast<float>(y), 1});
  const SampleQuality q = EvaluateSamples(samples, edges, valid, 4, 2);
  EXPECT_DOUBLE_EQ(q.on_edge, 0.5);
  EXPECT_DOUBLE_EQ(q.edge_density, 1.0 / 80.0);
  EXPECT_DOUBLE_EQ(q.ratio, 40.0);
  EXPECT_DOUBLE_EQ(q.blocks_covered, 4);  // two columns of blocks, both rows each
  EXPECT_DOUBLE_EQ(q.largest_block_share, 0.25);
}

// The paper's Fig. 4 claim, quantified on the simulated rpg room: AA samples lie on true edges
// far more often than random pixels, and spread over more blocks than ESVO's newest events at
// the same point count.
TEST(EdgeTruth, AaSamplesLieOnEdgesAndSpreadWiderThanNewestEvents) {
  const SimulationWorld world = World("rpg", 3.0);
  std::vector<TimeNs> ticks;
  for (int k = 1; k <= 4; ++k)
    ticks.push_back(world.spline.t_begin_ns() + k * 600 * kNsPerMs);
  events::RepresentationConfig config;
  config.edge_sampling.num_points = 1500;
  const SamplingComparison c = *CompareEdgeSampling(world, ticks, config, {});
  EXPECT_EQ(c.ticks, 4);
  EXPECT_GT(c.aa.samples, 500u);
  // Dense textures make 40–50 % of the (±1 px) image edge, so the ratio is bounded by ~2.3.
  EXPECT_GT(c.aa.on_edge, 0.85);
  EXPECT_GT(c.aa.ratio, 1.8);
  EXPECT_GE(c.aa.blocks_covered, c.esvo.blocks_covered);
  EXPECT_LT(c.aa.largest_block_share, c.esvo.largest_block_share);
  std::printf(
      "rpg preset, 4 ticks: AA %zu samples, on edge %.3f (density %.3f, ratio %.2f), "
      "blocks %.1f / %.1f, largest share %.3f; ESVO on edge %.3f (ratio %.2f), blocks "
      "%.1f, largest share %.3f\n",
      c.aa.samples, c.aa.on_edge, c.aa.edge_density, c.aa.ratio, c.aa.blocks_covered,
      c.aa.blocks_with_edges, c.aa.largest_block_share, c.esvo.on_edge, c.esvo.ratio,
      c.esvo.blocks_covered, c.esvo.largest_block_share);
}

}  // namespace
}  // namespace aavio::sim
