#include "aavio/mapping/depth_fusion.hpp"

#include <gtest/gtest.h>

#include <random>
#include <utility>

#include "aavio/geometry/rotation.hpp"
#include "aavio/mapping/local_map.hpp"
#include "aavio/mapping/mapping_test_utils.hpp"
#include "aavio/mapping/sgm_bootstrap.hpp"

namespace aavio::mapping {
namespace {

DepthPoint Point(float u, float v, double rho, double sigma, double nu = 2.182) {
  DepthPoint p;
  p.u = u, p.v = v, p.rho = rho, p.nu = nu;
  p.s2 = sigma * sigma * (nu - 2.0) / nu;
  p.residual = 10.0;
  return p;
}

TEST(StudentTFusion, BecomesInverseVarianceAveragingForLargeNu) {
  const DepthPoint a = Point(0, 0, 0.10, 0.01, 1e6), b = Point(0, 0, 0.12, 0.02, 1e6);
  const DepthPoint f = FuseStudentT(a, b);
  const double wa = 1 / 1e-4, wb = 1 / 4e-4;
  EXPECT_NEAR(f.rho, (wa * 0.10 + wb * 0.12) / (wa + wb), 1e-9);
  EXPECT_NEAR(f.variance(), 1.0 / (wa + wb), 1e-9);
  EXPECT_EQ(f.age, 1);
  // Heavy tails: a disagreement inflates the fused scale.
  const DepthPoint t = FuseStudentT(Point(0, 0, 0.10, 0.01), Point(0, 0, 0.13, 0.01));
  const DepthPoint agree = FuseStudentT(Point(0, 0, 0.10, 0.01), Point(0, 0, 0.10, 0.01));
  EXPECT_GT(t.s2, agree.s2);
  EXPECT_TRUE(Compatible(Point(0, 0, 0.10, 0.01), Point(0, 0, 0.115, 0.01), 2.0));
  EXPECT_FALSE(Compatible(Point(0, 0, 0.10, 0.01), Point(0, 0, 0.13, 0.01), 2.0));
}

TEST(Propagation, InverseDepthJacobianMatchesFiniteDifferences) {
  const RectifiedStereo stereo = testing::SmallStereo();
  geometry::RigidTransform T;
  T.R = geometry::ExpSO3(Eigen::Vector3d(0.02, -0.05, 0.03));
  T.t = {0.2, -0.1, -0.8};
  const DepthPoint p = Point(70.3f, 50.8f, 0.1, 0.01);
  DepthPoint moved, nudged;
  ASSERT_TRUE(Propagate(p, T, stereo, &moved));
  const double h = 1e-7;
  DepthPoint q = p;
  q.rho += h;
  ASSERT_TRUE(Propagate(q, T, stereo, &nudged));
  const double J = (nudged.rho - moved.rho) / h;
  EXPECT_NEAR(std::sqrt(moved.s2 / p.s2), std::abs(J), 1e-5 * std::abs(J));
  // And the geometry: the 3-D point is the same one.
  const Eigen::Vector3d before = T * p.Point(stereo), after = moved.Point(stereo);
  EXPECT_NEAR((before - after).norm(), 0.0, 1e-6);
}

TEST(DepthMap, FusionRules) {
  const RectifiedStereo stereo = testing::SmallStereo();
  FusionConfig config;
  config.radius = 1;
  DepthMap map(stereo, {}, 0);
  map.Fuse(Point(10.2f, 20.7f, 0.10, 0.01), config);
  EXPECT_EQ(map.size(), 9u);  // 3×3 cells around (10, 20)
  ASSERT_NE(map.At(11, 21), nullptr);
  EXPECT_EQ(map.At(11, 21)->u, 11.0f);                 // snapped to its cell
  map.Fuse(Point(10.0f, 20.0f, 0.105, 0.01), config);  // compatible: fused, age 1
  EXPECT_EQ(map.At(10, 20)->age, 1);
  EXPECT_NEAR(map.At(10, 20)->rho, 0.1025, 1e-9);
  // Incompatible and farther (smaller ρ) behind a clearly closer point: ignored.
  map.Fuse(Point(10.0f, 20.0f, 0.03, 0.001), config);
  EXPECT_NEAR(map.At(10, 20)->rho, 0.1025, 1e-9);
  // Incompatible, closer, better in variance and residual: replaces.
  DepthPoint better = Point(30.0f, 40.0f, 0.2, 0.001);
  map.Fuse(Point(30.0f, 40.0f, 0.1, 0.01), config);
  better.residual = 1.0;
  map.Fuse(better, config);
  EXPECT_NEAR(map.At(30, 40)->rho, 0.2, 1e-12);
  // Cleaning: points that were never fused (age 0) go.
  const std::size_t before = map.size();
  map.Clean(1.0, 0.001, 0.25);
  EXPECT_LT(map.size(), before);
  EXPECT_NE(map.At(10, 20), nullptr);
  EXPECT_EQ(map.At(12, 22), nullptr);
}

// confirm_across_batches: two neighbouring samples of one batch share cells but do not confirm
// each other; an estimate of another batch does.
TEST(DepthFusion, OnlyOtherBatchesConfirm) {
  const RectifiedStereo stereo = testing::SmallStereo();
  MappingConfig config;
  config.fusion.max_frames = 2;
  const std::vector<DepthPoint> pair = {Point(50.0f, 60.0f, 0.1, 0.01),
                                        Point(51.0f, 60.0f, 0.1, 0.01)};
  auto cells = [&](bool across, bool confirmed_by_next_batch) {
    config.fusion.confirm_across_batches = across;
    DepthFusion fusion(stereo, config.fusion,
                       {config.depth_refinement.max_inv_depth_stddev, config.inv_depth_range(),
                        config.regularization.enabled});
    fusion.Add(StereoKind::kStatic, {0, {}, pair});
    const DepthPoint elsewhere = Point(20.0f, 30.0f, 0.1, 0.01);
    fusion.Add(StereoKind::kStatic,
               {1, {}, {confirmed_by_next_batch ? Point(50.0f, 60.0f, 0.1, 0.01) : elsewhere}});
    EXPECT_TRUE(fusion.full());
    const DepthMap map = fusion.Fuse({}, 2);
    int around_pair = 0;
    for (const DepthPoint& p : map.Points())
      around_pair += p.u >= 49.0f && p.u <= 52.0f && p.v >= 59.0f && p.v <= 61.0f;
    return around_pair;
  };
  EXPECT_EQ(cells(false, false), 6);  // the reference: the 2×3 shared cells count as confirmed
  EXPECT_EQ(cells(true, false), 0);   // ... which only the same batch's neighbour did
  EXPECT_EQ(cells(true, true), 9);    // the 3×3 cells of the later batch's estimate at (50, 60)
}

// Regularisation as docs/mapping.md states it (ESVO's rpg values: 5 px, 8 and 8 neighbours),
// by a plain scan of every cell of the window: the reference the map's own (bitset-indexed,
// parallel) pass must reproduce exactly.
std::vector<DepthPoint> RegularizeByScan(const DepthMap& map) {
  const int w = map.stereo().width, h = map.stereo().height, r = 5;
  std::vector<DepthPoint> out;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const DepthPoint* p = map.At(x, y);
      if (p == nullptr) continue;
      int neighbours = 0;
      std::vector<DepthPoint> close;
      for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy) {
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
          const DepthPoint* q = map.At(xx, yy);
          if (q == nullptr || (xx == x && yy == y)) continue;
          ++neighbours;
          if (Compatible(*p, *q, kCompatibilitySigmas)) close.push_back(*q);
        }
      }
      DepthPoint result = *p;
      if (neighbours > 8) {
        if (static_cast<int>(close.size()) <= 8) continue;  // removed
        DepthPoint fused = *p;
        for (const DepthPoint& q : close)
          fused = FuseStudentT(fused, q);
        result.rho = fused.rho;
      }
      out.push_back(result);
    }
  }
  return out;
}

TEST(DepthMap, RegularizationMatchesAPlainScanOfTheRule) {
  // 150 px wide, so windows straddle the 64-cell words of the occupancy bitsets; clusters of
  // points on two depths with some outliers, sparse elsewhere.
  const RectifiedStereo stereo = testing::SmallStereo(150, 90);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const int seed : {7, 8}) {
    rng.seed(static_cast<std::mt19937::result_type>(seed));
    DepthMap map(stereo, {}, 0);
    FusionConfig fusion;
    fusion.radius = 0;
    for (int i = 0; i < 3000; ++i) {
      const float u = static_cast<float>(unit(rng) * 149.0),
                  v = static_cast<float>(unit(rng) * 89.0);
      const bool near_surface = u < 75.0f;
      double rho = (near_surface ? 0.5 : 0.2) + 0.01 * (unit(rng) - 0.5);
      if (unit(rng) < 0.05) rho *= 2.0;  // an outlier
      map.Fuse(Point(u, v, rho, 0.005 + 0.01 * unit(rng)), fusion);
    }
    const std::vector<DepthPoint> expected = RegularizeByScan(map);
    const std::size_t before = map.size();
    std::size_t smoothed = 0;  // points the rule moves (so the comparison below means something)
    for (const DepthPoint& e : expected)
      smoothed += map.At(static_cast<int>(e.u), static_cast<int>(e.v))->rho != e.rho ? 1 : 0;
    EXPECT_GT(smoothed, expected.size() / 2) << "seed " << seed;
    map.Regularize();
    ASSERT_EQ(map.size(), expected.size()) << "seed " << seed;
    EXPECT_LT(map.size(), before) << "seed " << seed;  // the outliers went
    for (const DepthPoint& e : expected) {
      const DepthPoint* got = map.At(static_cast<int>(e.u), static_cast<int>(e.v));
      ASSERT_NE(got, nullptr) << e.u << "," << e.v;
      EXPECT_EQ(got->rho, e.rho) << e.u << "," << e.v << " seed " << seed;
    }
  }
}

TEST(DepthFusion, FifoPoliciesAndPropagation) {
  const RectifiedStereo stereo = testing::SmallStereo();
  MappingConfig config;
  config.fusion.max_frames = 3;
  DepthFusion fusion(stereo, config.fusion,
                     {config.depth_refinement.max_inv_depth_stddev, config.inv_depth_range(),
                      config.regularization.enabled});
  for (int k = 0; k < 5; ++k) {
    // const_frames publishes (docs/mapping.md) and cleans once max_frames batches are in.
    EXPECT_EQ(fusion.ready_to_publish(), k >= 3) << k;
    EXPECT_EQ(fusion.full(), k >= 3) << k;
    DepthBatch batch{k, {}, {Point(50.0f + k, 60.0f, 0.1, 0.01)}};
    fusion.Add(StereoKind::kStatic, batch);
  }
  EXPECT_EQ(fusion.batches(), 3u);
  EXPECT_TRUE(fusion.full());
  // A temporal batch is kept in its own FIFO; an unconfirmed temporal point is cleaned like a
  // static one.
  DepthPoint temporal = Point(100.0f, 30.0f, 0.05, 0.01);
  temporal.kind = StereoKind::kTemporal;
  fusion.Add(StereoKind::kTemporal, {5, {}, {temporal}});
  geometry::RigidTransform forward;
  forward.t = {0.0, 0.0, -1.0};  // the new frame is 1 m behind: points at 10 m are now at 11 m
  const DepthMap map = fusion.Fuse(forward, 6);
  ASSERT_GT(map.size(), 0u);
  for (const DepthPoint& p : map.Points()) {
    EXPECT_NE(p.kind, StereoKind::kTemporal);
    EXPECT_NEAR(1.0 / p.rho, 11.0, 1e-6);
  }
  config.fusion.strategy = FusionStrategy::kConstPoints;
  config.fusion.max_points = 10;
  DepthFusion by_points(stereo, config.fusion,
                        {config.depth_refinement.max_inv_depth_stddev, config.inv_depth_range(),
                         config.regularization.enabled});
  for (int k = 0; k < 10; ++k) {
    DepthBatch batch{k, {}, std::vector<DepthPoint>(6, Point(50.0f, 60.0f, 0.1, 0.01))};
    by_points.Add(StereoKind::kStatic, batch);
  }
  EXPECT_LE(by_points.stored_points(), 15u);  // ≤ 1.5 × max_points
}

// const_points publishes (docs/mapping.md) beyond half of max_points static points and cleans
// from max_points on.
TEST(DepthFusion, ConstPointsPublishesFromHalfAndCleansWhenFull) {
  const RectifiedStereo stereo = testing::SmallStereo();
  MappingConfig config;
  config.fusion.strategy = FusionStrategy::kConstPoints;
  config.fusion.max_points = 10;
  DepthFusion by_points(stereo, config.fusion,
                        {config.depth_refinement.max_inv_depth_stddev, config.inv_depth_range(),
                         config.regularization.enabled});
  auto add = [&](int n) {
    by_points.Add(StereoKind::kStatic,
                  {0, {}, std::vector<DepthPoint>(n, Point(50.0f, 60.0f, 0.1, 0.01))});
  };
  add(5);  // 5 points: half, not more
  EXPECT_FALSE(by_points.ready_to_publish());
  by_points.Add(StereoKind::kTemporal, {0, {}, std::vector<DepthPoint>(9, Point(5, 6, 0.1, 0.01))});
  EXPECT_FALSE(by_points.ready_to_publish());  // temporal points do not count
  add(1);
  EXPECT_TRUE(by_points.ready_to_publish());
  EXPECT_FALSE(by_points.full());
  add(4);
  EXPECT_TRUE(by_points.full());
}

// A sparse scene's few points a cycle never reach max_points: with full_at_max_frames the FIFO
// is full at max_frames batches, so its maps are cleaned and written.
TEST(DepthFusion, ConstPointsFillsOnBatchesWhereTheSceneIsSparse) {
  const RectifiedStereo stereo = testing::SmallStereo();
  MappingConfig config;
  config.fusion.strategy = FusionStrategy::kConstPoints;
  config.fusion.max_points = 5000;
  config.fusion.max_frames = 4;
  DepthFusion sparse(stereo, config.fusion,
                     {config.depth_refinement.max_inv_depth_stddev, config.inv_depth_range(),
                      config.regularization.enabled});
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(sparse.full(), k >= 4) << k;
    EXPECT_EQ(sparse.ready_to_publish(), k >= 4) << k;
    sparse.Add(StereoKind::kStatic,
               {k, {}, std::vector<DepthPoint>(15, Point(50.0f + k, 60.0f, 0.1, 0.01))});
  }
  EXPECT_EQ(sparse.stored_points(), 150u);  // trimmed by points only, as the reference codes
  // The reference codes' rule: points alone.
  config.fusion.full_at_max_frames = false;
  DepthFusion by_points(stereo, config.fusion,
                        {config.depth_refinement.max_inv_depth_stddev, config.inv_depth_range(),
                         config.regularization.enabled});
  for (int k = 0; k < 10; ++k)
    by_points.Add(StereoKind::kStatic,
                  {k, {}, std::vector<DepthPoint>(15, Point(50.0f, 60.0f, 0.1, 0.01))});
  EXPECT_FALSE(by_points.full());
  EXPECT_FALSE(by_points.ready_to_publish());
}

// Edge samples on a 3-px grid inside the small stereo pair's overlap.
std::vector<Eigen::Vector2f> SampleGrid() {
  std::vector<Eigen::Vector2f> points;
  for (int v = 20; v < 100; v += 3)
    for (int u = 60; u < 140; u += 3)
      points.emplace_back(u, v);
  return points;
}

// A textured 8-bit time-surface pair whose right image is the left shifted by `disparity_px`.
std::pair<cv::Mat, cv::Mat> TexturePair(double disparity_px) {
  cv::Mat left8, right8;
  const cv::Mat left = testing::Texture(160, 120, 5);
  left.convertTo(left8, CV_8U);
  testing::Shifted(left, disparity_px, 0.0).convertTo(right8, CV_8U);
  return {left8, right8};
}

TEST(SgmBootstrap, DepthOfAShiftedTexture) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const auto [left8, right8] = TexturePair(16.0);
  const std::vector<Eigen::Vector2f> points = SampleGrid();
  MappingConfig config;
  const Expected<std::vector<DepthPoint>> sgm =
      BootstrapWithSgm(left8, right8, points, stereo, config.depth_refinement.student_t_nu,
                       config.inv_depth_range());
  ASSERT_TRUE(sgm.ok()) << sgm.status().message();
  int right = 0;
  for (const DepthPoint& p : *sgm)
    right += std::abs(stereo.Disparity(p.rho) - 16.0) < 0.5;
  EXPECT_GT(right, static_cast<int>(sgm->size()) * 9 / 10);
  EXPECT_GT(sgm->size(), points.size() / 2);
}

TEST(SgmBootstrap, AWideRigsDisparitiesLeaveHalfTheImage) {
  // Depths whose disparities run from 40 to 200 px on a 160 px wide pair (a wide baseline close
  // up): searching 0-207 would leave no column; the search is 40-119, found right of column 120.
  const RectifiedStereo stereo = testing::SmallStereo();
  const auto [left8, right8] = TexturePair(60.0);
  MappingConfig config;
  config.inv_depth_min = stereo.InvDepthOfDisparity(40.0);
  config.inv_depth_max = stereo.InvDepthOfDisparity(200.0);
  const Expected<std::vector<DepthPoint>> sgm =
      BootstrapWithSgm(left8, right8, SampleGrid(), stereo, config.depth_refinement.student_t_nu,
                       config.inv_depth_range());
  ASSERT_TRUE(sgm.ok()) << sgm.status().message();
  int right = 0;
  for (const DepthPoint& p : *sgm) {
    EXPECT_GE(p.u, 120.0f);
    right += std::abs(stereo.Disparity(p.rho) - 60.0) < 0.5;
  }
  EXPECT_GT(right, static_cast<int>(sgm->size()) * 9 / 10);
}

}  // namespace
}  // namespace aavio::mapping
