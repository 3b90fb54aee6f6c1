#include "aavio/eval/depth_error.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace aavio::eval {
namespace {

TEST(DepthError, ErrorsAndCompletenessOnAPlane) {
  const PinholeCamera camera{40, 30, 50.0, 20.0, 15.0, 5.0};  // f·b = 5 px·m: 0.5 px at 10 m
  cv::Mat depth(30, 40, CV_32FC1, cv::Scalar(10.0f));
  cv::Mat edges(30, 40, CV_8UC1, cv::Scalar(0));
  edges.row(10).setTo(255);  // a near-horizontal edge
  edges.col(30).setTo(128);  // an other edge: 30 pixels, one of them taken from the row (39 left)
  geometry::RigidTransform T_world_cam;
  T_world_cam.t = {0.0, 0.0, -2.0};  // camera 2 m behind the world origin
  // Estimates on the row, 1 % too far, at every 3rd pixel (±1 px covers the whole row).
  std::vector<Eigen::Vector3d> points;
  for (int x = 1; x < 40; x += 3) {
    const double z = 10.1;
    points.emplace_back((x - 20.0) / 50.0 * z, (10 - 15.0) / 50.0 * z, z - 2.0);  // world
  }
  DepthErrorAccumulator acc(camera);
  acc.Add(points, depth, edges, T_world_cam);
  const DepthErrorSummary s = acc.Summary();
  EXPECT_EQ(s.points, points.size());
  EXPECT_NEAR(s.mean_m, 0.1, 1e-9);
  EXPECT_NEAR(s.median_m, 0.1, 1e-9);
  EXPECT_NEAR(s.relative, 0.01, 1e-9);
  EXPECT_NEAR(s.relative_median, 0.01, 1e-9);
  EXPECT_DOUBLE_EQ(s.outliers, 0.0);
  EXPECT_NEAR(s.mean_true_depth_m, 10.0, 1e-9);
  // 5 / 10 − 5 / 10.1 px.
  EXPECT_NEAR(s.disparity_error_px, 5.0 / 10.0 - 5.0 / 10.1, 1e-9);
  EXPECT_NEAR(s.disparity_error_median_px, 5.0 / 10.0 - 5.0 / 10.1, 1e-9);
  // Points at x = 1, 4, …, 37 cover x = 0…38 (±1 px): 38 of the row's 39 pixels.
  EXPECT_NEAR(s.completeness_horizontal, 38.0 / 39.0, 1e-12);
  // The column: rows 9–11 are within 1 px of the row's points: 3 of its 30 pixels.
  EXPECT_NEAR(s.completeness_other, 3.0 / 30.0, 1e-12);
  EXPECT_EQ(s.points_horizontal, points.size());
  EXPECT_EQ(s.points_discontinuity, 0u);
  EXPECT_NEAR(s.relative_continuous, 0.01, 1e-9);
}

// Block coverage: of a 64×48 image's twelve 16-px blocks, those crossed by an edge (at least 16
// edge pixels) count; a block reached by an estimate anywhere inside it is covered, however few
// of its edge pixels the estimate is near. Edge pixels too few for a block (a 10-px stub) and
// estimates in blocks without structure count for nothing; the last, partial column of blocks of
// a 70-px image is left out.
TEST(DepthError, BlockCoverageCountsBlocksWithStructureReached) {
  const PinholeCamera camera{70, 48, 50.0, 35.0, 24.0};
  cv::Mat depth(48, 70, CV_32FC1, cv::Scalar(10.0f));
  cv::Mat edges(48, 70, CV_8UC1, cv::Scalar(0));
  edges.row(8).colRange(0, 64).setTo(255);    // across the top row of blocks (4 blocks)
  edges.col(40).rowRange(16, 48).setTo(128);  // down blocks (2, 1) and (2, 2)
  edges.row(40).colRange(0, 10).setTo(128);   // a stub: not enough for block (0, 2)
  edges.col(66).setTo(128);                   // in the partial column: not a block
  auto at = [&](int x, int y) {
    const double z = 10.0;
    return Eigen::Vector3d((x - 35.0) / 50.0 * z, (y - 24.0) / 50.0 * z, z);
  };
  const std::vector<Eigen::Vector3d> points = {
      at(3, 3),    // block (0, 0), five rows from its edge: reaches the block, not the edge
      at(20, 8),   // block (1, 0), on the edge
      at(42, 30),  // block (2, 1)
      at(5, 40),   // block (0, 2): only the stub, no structure
      at(66, 20),  // the partial column
  };
  DepthErrorAccumulator acc(camera);
  acc.Add(points, depth, edges, geometry::RigidTransform());
  const DepthErrorSummary s = acc.Summary();
  EXPECT_NEAR(s.block_coverage, 3.0 / 6.0, 1e-12);        // blocks (0,0) (1,0) (2,1) of 6
  acc.Add({}, depth, edges, geometry::RigidTransform());  // an empty map halves it
  EXPECT_NEAR(acc.Summary().block_coverage, 3.0 / 12.0, 1e-12);
}

// A box at 5 m (columns 20 and right of it) in front of a wall at 20 m: an estimate at the box's
// depth one pixel outside its silhouette is scored 75 % off, and apart from the others.
TEST(DepthError, PointsOnDepthDiscontinuitiesAreScoredApart) {
  const PinholeCamera camera{40, 30, 50.0, 20.0, 15.0};
  cv::Mat depth(30, 40, CV_32FC1, cv::Scalar(20.0f));
  depth.colRange(20, 40).setTo(5.0f);
  auto at = [&](int x, int y, double z) {
    return Eigen::Vector3d((x - 20.0) / 50.0 * z, (y - 15.0) / 50.0 * z, z);
  };
  const std::vector<Eigen::Vector3d> points = {
      at(19, 10, 5.0),  // silhouette: the box's depth on the wall's pixel
      at(30, 10, 5.1),  // the box, 2 % off
      at(5, 10, 20.4),  // the wall, 2 % off
  };
  DepthErrorAccumulator acc(camera);
  acc.Add(points, depth, cv::Mat(), geometry::RigidTransform());
  const DepthErrorSummary s = acc.Summary();
  EXPECT_EQ(s.points, 3u);
  EXPECT_EQ(s.points_discontinuity, 1u);
  EXPECT_NEAR(s.relative_discontinuity, 0.75, 1e-6);
  EXPECT_NEAR(s.relative_continuous, 0.02, 1e-6);
  EXPECT_NEAR(s.relative, (0.75 + 0.04) / 3.0, 1e-6);
}

// Kept points (for the report's plots) carry where they fell, both depths, their kind and their
// frame; none are kept unless asked for.
TEST(DepthError, KeptPointsCarryTheirKindAndFrame) {
  const PinholeCamera camera{40, 30, 50.0, 20.0, 15.0};
  cv::Mat depth(30, 40, CV_32FC1, cv::Scalar(20.0f));
  depth.colRange(20, 40).setTo(5.0f);
  cv::Mat edges(30, 40, CV_8UC1, cv::Scalar(0));
  edges.at<std::uint8_t>(10, 30) = 255;  // a near-horizontal edge pixel
  auto at = [&](int x, int y, double z) {
    return Eigen::Vector3d((x - 20.0) / 50.0 * z, (y - 15.0) / 50.0 * z, z);
  };
  DepthErrorAccumulator acc(camera);
  acc.Add({at(5, 10, 20.4)}, depth, edges, geometry::RigidTransform());
  EXPECT_TRUE(acc.points().empty());
  acc.KeepPoints(true);
  acc.Add({at(19, 10, 5.0), at(30, 10, 5.1)}, depth, edges, geometry::RigidTransform());
  ASSERT_EQ(acc.points().size(), 2u);
  const ScoredDepthPoint& silhouette = acc.points()[0];
  EXPECT_NEAR(silhouette.u, 19.0f, 1e-4f);
  EXPECT_NEAR(silhouette.v, 10.0f, 1e-4f);
  EXPECT_EQ(silhouette.z_gt_m, 20.0f);
  EXPECT_NEAR(silhouette.z_est_m, 5.0f, 1e-5f);
  EXPECT_EQ(silhouette.kind, ScoredDepthPoint::kDiscontinuity);
  EXPECT_EQ(silhouette.frame, 1u);
  EXPECT_EQ(acc.points()[1].kind, ScoredDepthPoint::kHorizontal);
  EXPECT_EQ(acc.points()[1].z_gt_m, 5.0f);
}

// The same matching error (0.25 px of disparity) on a near and a far plane: the relative depth
// error grows with depth, the disparity error does not; without f·b it is not computed.
TEST(DepthError, DisparityErrorDoesNotGrowWithDepth) {
  const double fb = 20.0;
  auto score = [&](double z_gt, double fb_px_m) {
    const PinholeCamera camera{40, 30, 50.0, 20.0, 15.0, fb_px_m};
    cv::Mat depth(30, 40, CV_32FC1, cv::Scalar(static_cast<float>(z_gt)));
    const double z = fb / (fb / z_gt - 0.25);  // 0.25 px less disparity: farther
    DepthErrorAccumulator acc(camera);
    acc.Add({Eigen::Vector3d(0.0, 0.0, z)}, depth, cv::Mat(), geometry::RigidTransform());
    return acc.Summary();
  };
  const DepthErrorSummary near = score(4.0, fb), far = score(16.0, fb);
  EXPECT_NEAR(near.disparity_error_px, 0.25, 1e-5);
  EXPECT_NEAR(far.disparity_error_px, 0.25, 1e-5);
  EXPECT_NEAR(near.mean_true_depth_m, 4.0, 1e-6);
  EXPECT_NEAR(far.mean_true_depth_m, 16.0, 1e-6);
  EXPECT_NEAR(near.relative, 0.25 / (fb / 4.0 - 0.25), 1e-6);  // 5.3 %
  EXPECT_NEAR(far.relative, 0.25 / (fb / 16.0 - 0.25), 1e-6);  // 25 %
  EXPECT_DOUBLE_EQ(score(4.0, 0.0).disparity_error_px, 0.0);
}

// The figures up to a depth cutoff take only the points and the edge pixels whose ground-truth
// depth is within it: a near-horizontal edge across a plane at 8 m (left half) and one at 25 m
// (right half), estimates 2 % off covering most of the near half and one 10 % off on the far one.
TEST(DepthError, CutoffsScoreOnlyWhatLiesWithinThem) {
  ASSERT_EQ(kDepthCutoffsM.size(), 3u);
  const PinholeCamera camera{40, 30, 50.0, 20.0, 15.0};
  cv::Mat depth(30, 40, CV_32FC1, cv::Scalar(8.0f));
  depth.colRange(20, 40).setTo(25.0f);
  cv::Mat edges(30, 40, CV_8UC1, cv::Scalar(0));
  edges.row(10).setTo(255);
  auto at = [](int x, double z) {
    return Eigen::Vector3d((x - 20.0) / 50.0 * z, (10 - 15.0) / 50.0 * z, z);
  };
  std::vector<Eigen::Vector3d> points;
  for (int x = 1; x <= 16; x += 3)
    points.push_back(at(x, 8.0 * 1.02));  // cover x = 0…17: 18 of the near half's 20 pixels
  points.push_back(at(31, 25.0 * 1.1));   // covers x = 30…32 of the far half
  DepthErrorAccumulator acc(camera);
  acc.Add(points, depth, edges, geometry::RigidTransform());
  const DepthErrorSummary s = acc.Summary();
  EXPECT_NEAR(s.completeness_horizontal, 21.0 / 40.0, 1e-12);
  for (std::size_t c : {0u, 1u}) {  // 10 and 20 m: the near plane only
    const DepthCutoffSummary& k = s.cutoffs[c];
    EXPECT_DOUBLE_EQ(k.max_depth_m, kDepthCutoffsM[c]);
    EXPECT_EQ(k.points, 6u);
    EXPECT_NEAR(k.relative, 0.02, 1e-9);
    EXPECT_NEAR(k.mean_m, 0.16, 1e-9);
    EXPECT_NEAR(k.completeness, 18.0 / 20.0, 1e-12);
    EXPECT_NEAR(k.completeness_horizontal, 18.0 / 20.0, 1e-12);
  }
  const DepthCutoffSummary& all = s.cutoffs[2];  // 30 m: both planes
  EXPECT_EQ(all.points, 7u);
  EXPECT_NEAR(all.relative, (6 * 0.02 + 0.1) / 7.0, 1e-9);
  EXPECT_NEAR(all.completeness_horizontal, 21.0 / 40.0, 1e-12);
}

}  // namespace
}  // namespace aavio::eval
