#include "aavio/mapping/mapper.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "aavio/mapping/depth_map.hpp"
#include "aavio/mapping/mapping_test_utils.hpp"
#include "aavio/mapping/sgm_bootstrap.hpp"

namespace aavio::mapping {
namespace {

using testing::PlaneObservation;

TEST(Mapper, MapsAPlaneFromSgmThenCycles) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const std::shared_ptr<events::Observation> obs = PlaneObservation();
  MappingConfig config;
  config.bootstrap.min_points = 100;
  config.max_points = 5000;
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  Mapper mapper(stereo, valid, config);
  ASSERT_TRUE(mapper.Initialize({obs, {}}).ok());
  const double z = stereo.fb() / 16.0;
  auto median_depth = [&] {
    std::vector<double> depths;
    for (const DepthPoint& p : mapper.local_map()->points)
      depths.push_back(1.0 / p.rho);
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    return depths[depths.size() / 2];
  };
  EXPECT_NEAR(median_depth(), z, 0.05 * z);
  for (int k = 1; k <= 6; ++k) {
    MappingCycleReport report;
    auto next = std::make_shared<events::Observation>(*obs);
    next->t_ns = k * 50 * kNsPerMs;
    ASSERT_TRUE(mapper.Update({next, {}}, nullptr, &report).ok());
    EXPECT_GT(report.static_points, 500);
    EXPECT_EQ(report.temporal_candidates, 0);  // no partner: near-horizontal pixels are skipped
  }
  EXPECT_NEAR(median_depth(), z, 0.01 * z);
  const LocalMapPtr map = mapper.local_map();
  ASSERT_EQ(map->points.size(), map->points_world.size());
  EXPECT_NEAR(map->points_world.front().z(), 1.0 / map->points.front().rho, 1e-9);
  mapper.Reset();
  EXPECT_FALSE(mapper.initialized());
  EXPECT_EQ(mapper.local_map(), nullptr);
}

// As the reference codes (docs/mapping.md): the bootstrap map is published, then nothing until
// the FIFO is full (max_frames batches, the bootstrap's included) and cleaned; with
// fusion.publish_while_filling every cycle publishes, the maps before the FIFO is full marked
// provisional (not confirmed).
TEST(Mapper, PublishesTheBootstrapThenOnlyFullFifos) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const std::shared_ptr<events::Observation> obs = PlaneObservation();
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  for (const bool while_filling : {false, true}) {
    SCOPED_TRACE(while_filling ? "publish_while_filling" : "reference");
    MappingConfig config;
    config.bootstrap.min_points = 100;
    config.max_points = 5000;
    config.fusion.max_frames = 4;
    config.fusion.publish_while_filling = while_filling;
    Mapper mapper(stereo, valid, config);
    ASSERT_TRUE(mapper.Initialize({obs, {}}).ok());
    LocalMapPtr published = mapper.local_map();
    ASSERT_NE(published, nullptr);
    EXPECT_TRUE(published->confirmed);
    for (int k = 1; k <= 5; ++k) {
      MappingCycleReport report;
      auto next = std::make_shared<events::Observation>(*obs);
      next->t_ns = k * 50 * kNsPerMs;
      ASSERT_TRUE(mapper.Update({next, {}}, nullptr, &report).ok());
      const bool full = k >= 3;  // batches: the bootstrap's + k
      const bool expected = while_filling || full;
      EXPECT_EQ(report.published, expected) << "cycle " << k;
      EXPECT_EQ(mapper.local_map() != published, expected) << "cycle " << k;
      EXPECT_GT(report.map_points, 0);
      if (expected) {
        EXPECT_EQ(mapper.local_map()->t_ns, next->t_ns);
        EXPECT_EQ(mapper.local_map()->confirmed, full) << "cycle " << k;
      }
      published = mapper.local_map();
    }
  }
}

// bootstrap.method = block_matching: the cycle's static stereo on the first observation, every
// point refined and old enough to survive the first cleanings.
// A first map: min_points in any scene, or fewer where they cover enough of the edges in view.
TEST(BootstrapConfig, AcceptsWhatTheSceneOffers) {
  BootstrapConfig b;                   // 500 points, or half the samples and at least 50
  EXPECT_TRUE(b.Accepts(500, 5000));   // the count, however many samples
  EXPECT_FALSE(b.Accepts(499, 5000));  // neither the count nor half the samples
  EXPECT_TRUE(b.Accepts(82, 107));     // a sparse scene: 77 % of its samples
  EXPECT_FALSE(b.Accepts(53, 107));    // under half of them
  EXPECT_FALSE(b.Accepts(49, 60));     // most of too few samples: under the registration floor
  b.min_coverage = 0.0;                // the reference codes: the count alone
  EXPECT_FALSE(b.Accepts(82, 107));
  const std::string why = b.Refusal("SGM", 82, 107, 300);
  EXPECT_NE(why.find("SGM bootstrap found 82 points at the 300 edge samples (107 of them not"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("mapping.bootstrap.min_coverage"), std::string::npos) << why;
}

TEST(Mapper, BootstrapsByBlockMatching) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const std::shared_ptr<events::Observation> obs = PlaneObservation();
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  MappingConfig config;
  config.bootstrap.method = BootstrapMethod::kBlockMatching;
  config.bootstrap.min_points = 100;
  config.max_points = 5000;
  Mapper mapper(stereo, valid, config);
  ASSERT_TRUE(mapper.Initialize({obs, {}}).ok());
  const LocalMapPtr map = mapper.local_map();
  ASSERT_GT(map->points.size(), 500u);
  const double rho = 16.0 / stereo.fb();
  for (const DepthPoint& p : map->points) {
    EXPECT_NEAR(p.rho, rho, 0.01 * rho);
    EXPECT_EQ(p.age, kMinAge);
    // Refined: σ from the Jacobian, far below SGM's fixed σ_ρ for a point this near.
    EXPECT_LT(std::sqrt(p.variance()), 0.1 * kSgmInvDepthStddev * 50.0);
  }

  config.bootstrap.min_points = 100000;
  config.bootstrap.min_coverage = 0.0;
  Mapper picky(stereo, valid, config);
  const Status status = picky.Initialize({obs, {}});
  EXPECT_EQ(status.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(status.message().find("block-matching bootstrap"), std::string::npos);
  EXPECT_NE(status.message().find("mapping.bootstrap.min_points"), std::string::npos);
  EXPECT_FALSE(picky.initialized());
}

// A first map's coverage counts the samples static stereo can match: a band of near-horizontal
// edges (no disparity along them) with three times as many samples as the rest of the view does
// not keep a well-matched rest from making a map.
TEST(Mapper, BootstrapCoverageLeavesOutNearHorizontalEdges) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const std::shared_ptr<events::Observation> obs = PlaneObservation();
  const cv::Rect band(0, 60, 160, 15);
  obs->ts_left(cv::Rect(0, 54, 160, 27)).setTo(0);  // no patch there to match either
  obs->grad_u(band).setTo(0.0f);
  obs->grad_v(band).setTo(1.0f);
  const std::size_t elsewhere = obs->samples.size();
  for (std::uint16_t v = 60; v < 75; ++v) {
    for (std::uint16_t u = 40; u < 150; ++u)
      obs->samples.push_back({u, v, static_cast<float>(u), static_cast<float>(v), 2});
  }
  ASSERT_GT(obs->samples.size(), 2 * elsewhere);
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  MappingConfig config;
  config.bootstrap.method = BootstrapMethod::kBlockMatching;
  config.bootstrap.min_points = 100000;  // coverage alone decides
  config.max_points = 5000;
  // Every matchable sample asked for: refused, and the message counts them.
  config.bootstrap.min_coverage = 1.0;
  const Status refused = Mapper(stereo, valid, config).Initialize({obs, {}});
  ASSERT_EQ(refused.code(), StatusCode::kFailedPrecondition);
  std::size_t points = 0, samples = 0, matchable = 0;
  ASSERT_EQ(std::sscanf(refused.message().c_str(),
                        "block-matching bootstrap found %zu points at the %zu edge samples (%zu",
                        &points, &samples, &matchable),
            3)
      << refused.message();
  EXPECT_EQ(samples, obs->samples.size());
  EXPECT_LT(matchable, samples / 2);
  EXPECT_LT(points, samples / 2);       // under half of all the samples
  EXPECT_GE(points, matchable / 2);     // but over half of those stereo can match
  config.bootstrap.min_coverage = 0.5;  // the default: accepted
  Mapper mapper(stereo, valid, config);
  const Status status = mapper.Initialize({obs, {}});
  EXPECT_TRUE(status.ok()) << status.message();
}

// The η split (the paper): near-horizontal samples go to temporal stereo only, the others to
// static stereo.
TEST(Mapper, NearHorizontalSamplesGoToTemporalStereo) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const std::shared_ptr<events::Observation> obs = PlaneObservation();
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  geometry::RigidTransform T_world_past;
  T_world_past.t = {0.0, -0.5, 0.0};
  const PosedObservation partner{obs, T_world_past};
  MappingConfig config;
  config.bootstrap.min_points = 100;
  config.max_points = 5000;
  Mapper mapper(stereo, valid, config);
  ASSERT_TRUE(mapper.Initialize({obs, {}}).ok());
  MappingCycleReport split;
  ASSERT_TRUE(mapper.Update({obs, {}}, &partner, &split).ok());
  EXPECT_GT(split.temporal_candidates, 20);  // the wave texture has near-horizontal edges
  EXPECT_GT(split.static_candidates, 20);
  EXPECT_EQ(split.static_candidates + split.temporal_candidates, split.samples);
}

// Temporal depths are refined on the AA maps: the partner is 0.5 m above, and its AA map agrees
// with a plane at 20.1 m while its time surface has the plane at 19 m (as if the newest edges had
// moved on); the temporal points say 20.1 m.
TEST(Mapper, TemporalDepthsFollowTheAaMaps) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const std::shared_ptr<events::Observation> obs = PlaneObservation();
  const double z_aa = stereo.fb() / 16.0, z_ts = 19.0, baseline_m = 0.5;
  auto past = std::make_shared<events::Observation>();
  testing::WaveTexture(160, 120, 7, 0.0, -stereo.f * baseline_m / z_aa)
      .convertTo(past->aa_map, CV_8U);
  testing::WaveTexture(160, 120, 7, 0.0, -stereo.f * baseline_m / z_ts)
      .convertTo(past->ts_left, CV_8U);
  geometry::RigidTransform T_world_past;
  T_world_past.t = {0.0, -baseline_m, 0.0};
  const PosedObservation partner{past, T_world_past};
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  MappingConfig config;
  config.max_points = 5000;
  config.eta = 1e9;  // every sample to temporal stereo
  config.fusion.publish_while_filling = true;
  Mapper mapper(stereo, valid, config);
  MappingCycleReport report;
  ASSERT_TRUE(mapper.Update({obs, {}}, &partner, &report).ok());
  EXPECT_EQ(report.static_candidates, 0);
  ASSERT_GT(report.temporal_points, 300);
  std::vector<double> depths;
  for (const DepthPoint& p : mapper.local_map()->points) {
    EXPECT_EQ(p.kind, StereoKind::kTemporal);
    depths.push_back(1.0 / p.rho);
  }
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  EXPECT_NEAR(depths[depths.size() / 2], z_aa, 0.005 * z_aa);
}

}  // namespace
}  // namespace aavio::mapping

namespace aavio::mapping {
namespace {

// Temporal points move from the pixel they were matched at to their sample's snapped position;
// static points and depths stay.
TEST(Mapper, TemporalPointsMoveOntoTheirSnappedSamples) {
  const std::vector<Eigen::Vector2f> matched_at = {{10, 20}, {11, 30}, {12, 40}, {13, 50}};
  const std::vector<Eigen::Vector2f> snapped = {{10, 21.5f}, {11, 29}, {12.5f, 40}, {13, 51}};
  auto point = [](float u, float v, StereoKind kind) {
    DepthPoint p;
    p.u = u;
    p.v = v;
    p.rho = 0.1;
    p.kind = kind;
    return p;
  };
  // Static points first (one at a temporal sample's pixel), then the temporal points that
  // survived refinement (the second sample's was culled).
  std::vector<DepthPoint> points = {
      point(10, 20, StereoKind::kStatic), point(50, 60, StereoKind::kStatic),
      point(10, 20, StereoKind::kTemporal), point(12, 40, StereoKind::kTemporal),
      point(13, 50, StereoKind::kTemporal)};
  MoveOntoNewestEdge(matched_at, snapped, &points);
  const std::vector<Eigen::Vector2f> expected = {
      {10, 20}, {50, 60}, {10, 21.5f}, {12.5f, 40}, {13, 51}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].u, expected[i].x()) << i;
    EXPECT_EQ(points[i].v, expected[i].y()) << i;
    EXPECT_EQ(points[i].rho, 0.1);
  }
}

}  // namespace
}  // namespace aavio::mapping
