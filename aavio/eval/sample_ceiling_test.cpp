#include "aavio/eval/sample_ceiling.hpp"

#include <gtest/gtest.h>

namespace aavio::eval {
namespace {

// A plane 10 m away with a near-horizontal edge on row 10, and a far patch (100 m, beyond the
// 50 m search range) in the top-left corner. Cycle 1 samples the row every 3rd pixel and the far
// patch; cycle 2 samples one pixel off the edge. Each sample stands for the 2×2 cells fusion
// gives an estimate at radius 0. Scoring only the newest cycle finds the row empty; scoring both
// covers it, at the true depth, without the far sample.
TEST(SampleCeiling, ScoresTheSamplesOfTheCyclesAMapFusesAtTheirTrueDepth) {
  const PinholeCamera camera{40, 30, 50.0, 20.0, 15.0};
  cv::Mat depth(30, 40, CV_32FC1, cv::Scalar(10.0f));
  depth(cv::Rect(0, 0, 6, 4)).setTo(100.0f);
  cv::Mat edges(30, 40, CV_8UC1, cv::Scalar(0));
  edges.row(10).setTo(255);
  geometry::RigidTransform T_world_cam;
  T_world_cam.t = {1.0, 0.0, -2.0};

  std::vector<Eigen::Vector2f> row, off_edge{{5.0f, 20.0f}};
  for (int x = 1; x < 40; x += 3)
    row.emplace_back(static_cast<float>(x), 10.0f);
  row.emplace_back(2.0f, 2.0f);  // the far patch: outside the depth range
  SampleCeiling ceiling(camera, 4.0, 50.0, 2);
  ceiling.AddCycle(row, depth, T_world_cam);
  ceiling.AddCycle(off_edge, depth, T_world_cam);
  ceiling.Score(1, depth, edges, T_world_cam);
  EXPECT_EQ(ceiling.Summary().points, 4u);  // one sample's 2×2 cells
  EXPECT_DOUBLE_EQ(ceiling.Summary().completeness_horizontal, 0.0);

  SampleCeiling both(camera, 4.0, 50.0, 2);
  both.AddCycle(row, depth, T_world_cam);
  both.AddCycle(off_edge, depth, T_world_cam);
  both.Score(2, depth, edges, T_world_cam);
  const DepthErrorSummary s = both.Summary();
  EXPECT_EQ(s.points, 14u * 4u);  // 13 samples on the row and the one off it; not the far one
  EXPECT_DOUBLE_EQ(s.completeness_horizontal, 1.0);
  EXPECT_NEAR(s.relative, 0.0, 1e-9);

  both.Clear();  // re-initialised: nothing stored
  both.Score(2, depth, edges, T_world_cam);
  EXPECT_EQ(both.Summary().frames, 2u);
  EXPECT_EQ(both.Summary().points, 14u * 4u);
  EXPECT_DOUBLE_EQ(both.Summary().completeness_horizontal, 0.5);
}

// With 3×3 cells (fusion radius ≥ 1) a sample at (20, 10) holds columns 19–21 of its row, and
// the ±1 px of completeness reaches 18–22; two samples sharing cells count them once.
TEST(SampleCeiling, CellsFollowTheFusionRadius) {
  const PinholeCamera camera{40, 30, 50.0, 20.0, 15.0};
  cv::Mat depth(30, 40, CV_32FC1, cv::Scalar(10.0f));
  cv::Mat edges(30, 40, CV_8UC1, cv::Scalar(0));
  edges.row(10).setTo(255);
  SampleCeiling ceiling(camera, 4.0, 50.0, 3);
  const std::vector<Eigen::Vector2f> samples{{20.0f, 10.0f}, {20.4f, 10.2f}};
  ceiling.AddCycle(samples, depth, geometry::RigidTransform());
  ceiling.Score(1, depth, edges, geometry::RigidTransform());
  EXPECT_EQ(ceiling.Summary().points, 9u);
  EXPECT_DOUBLE_EQ(ceiling.Summary().completeness_horizontal, 5.0 / 40.0);
}

}  // namespace
}  // namespace aavio::eval
