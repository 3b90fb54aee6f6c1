#include <gtest/gtest.h>

#include "aavio/mapping/depth_refinement.hpp"
#include "aavio/mapping/disparity_prediction.hpp"
#include "aavio/mapping/mapping_test_utils.hpp"
#include "aavio/mapping/static_stereo.hpp"
#include "aavio/mapping/temporal_stereo.hpp"
#include "aavio/mapping/zncc.hpp"

namespace aavio::mapping {
namespace {

MappingConfig Config() {
  MappingConfig c;
  c.inv_depth_min = 0.001;
  c.inv_depth_max = 0.25;  // disparity ≤ 80 px with f b = 321.6
  return c;
}

TEST(Zncc, CostOfEqualOppositeAndFlatPatches) {
  const cv::Mat a = testing::Texture(20, 10, 1);
  NormalizedPatch p;
  ASSERT_TRUE(PreparePatch(a.ptr<float>(), static_cast<int>(a.step1()), 7, 15, &p));
  EXPECT_NEAR(ZnccCost(p, a.ptr<float>(), static_cast<int>(a.step1())), 0.0, 1e-6);
  const cv::Mat inverted = 300.0f - a;  // anti-correlated, similar mean
  EXPECT_NEAR(ZnccCost(p, inverted.ptr<float>(), static_cast<int>(a.step1())), 1.0, 1e-6);
  const cv::Mat flat(10, 20, CV_32FC1, cv::Scalar(100));
  EXPECT_DOUBLE_EQ(ZnccCost(p, flat.ptr<float>(), static_cast<int>(flat.step1())), 0.5);
}

TEST(Zncc, MeansMoreThanFiveTimesApartCostOneHalf) {
  // A scaled copy correlates perfectly; scaled beyond a factor of 5 either way the mean rule
  // (decided from Σb before the other sums) gives no correlation.
  const cv::Mat a = testing::Texture(31, 5, 3);
  NormalizedPatch p;
  ASSERT_TRUE(PreparePatch(a.ptr<float>(), static_cast<int>(a.step1()), 5, 31, &p));
  for (const double scale : {0.21, 4.9, 0.19, 5.1}) {
    SCOPED_TRACE(scale);
    const cv::Mat b = a * scale;
    const double cost = ZnccCost(p, b.ptr<float>(), static_cast<int>(b.step1()));
    if (scale > 0.2 && scale < 5.0) {
      EXPECT_NEAR(cost, 0.0, 1e-6);
    } else {
      EXPECT_DOUBLE_EQ(cost, 0.5);
    }
  }
}

TEST(Zncc, RowSearchEqualsOneCostPerPosition) {
  const cv::Mat image = testing::Texture(160, 40, 5);
  const int stride = static_cast<int>(image.step1());
  NormalizedPatch p;
  ASSERT_TRUE(PreparePatch(image.ptr<float>(12) + 90, stride, 7, 15, &p));
  // Include a flat stretch (cost 0.5) and the patch's own position (cost 0).
  cv::Mat band = image.clone();
  band(cv::Rect(0, 12, 30, 7)).setTo(40.0f);
  const int count = 120;
  std::vector<double> costs(count);
  ZnccCostsAlongRow(p, band.ptr<float>(12) + 5, stride, count, costs.data());
  for (int j = 0; j < count; ++j) {
    SCOPED_TRACE(j);
    EXPECT_NEAR(costs[static_cast<std::size_t>(j)],
                ZnccCost(p, band.ptr<float>(12) + 5 + j, stride), 2e-5);
  }
  EXPECT_DOUBLE_EQ(costs[0], 0.5);
  EXPECT_NEAR(costs[85], 0.0, 1e-6);
}

// Left pixels on a grid over the middle of the 160×120 test images.
std::vector<Eigen::Vector2f> GridPoints() {
  std::vector<Eigen::Vector2f> points;
  for (int v = 20; v < 100; v += 9)
    for (int u = 40; u < 140; u += 11)
      points.emplace_back(u, v);
  return points;
}

TEST(StaticStereo, FindsTheShiftOfATexture) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const cv::Mat left = testing::Texture(160, 120, 2);
  const cv::Mat right = testing::Shifted(left, 12.0, 0.0);  // right(x) = left(x + 12): d = 12
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  MappingConfig config = Config();
  const std::vector<Eigen::Vector2f> points = GridPoints();
  const std::vector<Match> matches = MatchStatic({left, right, valid}, points, stereo,
                                                 config.static_stereo, config.inv_depth_range());
  EXPECT_GT(matches.size(), points.size() * 9 / 10);
  for (const Match& m : matches) {
    EXPECT_NEAR(stereo.Disparity(m.rho), 12.0, 1e-9);
    EXPECT_LT(m.cost, 0.01);
  }
  // A flat right image matches nothing.
  const cv::Mat flat(120, 160, CV_32FC1, cv::Scalar(50));
  EXPECT_TRUE(MatchStatic({left, flat, valid}, points, stereo, config.static_stereo,
                          config.inv_depth_range())
                  .empty());
}

// The left-right check keeps consistent matches and drops a match whose right patch finds a
// better partner elsewhere on the left row.
// A previous map of the plane at disparity `disparity` over the whole view (identity pose).
LocalMap PlaneMap(const RectifiedStereo& stereo, double disparity) {
  LocalMap map;
  for (int v = 4; v < stereo.height; v += 4) {
    for (int u = 4; u < stereo.width; u += 4) {
      DepthPoint p;
      p.u = static_cast<float>(u), p.v = static_cast<float>(v);
      p.rho = disparity / stereo.fb();
      map.points.push_back(p);
      map.points_world.push_back(p.Point(stereo));
    }
  }
  return map;
}

TEST(StaticStereo, SearchesWhereThePreviousMapPredictsAndFallsBackWhereItIsWrong) {
  const RectifiedStereo stereo = testing::SmallStereo();
  // A texture so smooth that one pixel off the truth still passes the cost threshold.
  cv::Mat left;
  cv::GaussianBlur(testing::Texture(160, 120, 2), left, cv::Size(0, 0), 4.0);
  const cv::Mat right = testing::Shifted(left, 12.0, 0.0);  // d = 12
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  const MappingConfig config = Config();
  const std::vector<Eigen::Vector2f> points = GridPoints();
  const std::vector<Match> full = MatchStatic({left, right, valid}, points, stereo,
                                              config.static_stereo, config.inv_depth_range());
  ASSERT_GT(full.size(), points.size() * 9 / 10);
  // A right prediction (12.3 px: window 10–15) gives the same matches; so does one next to the
  // truth (15.5 px: window 13–18), whose best then lies at the window's cut end, searched again
  // over the whole range.
  for (const double predicted : {12.3, 15.5}) {
    SCOPED_TRACE(predicted);
    const DisparityPrediction prediction(PlaneMap(stereo, predicted), {}, stereo);
    const std::vector<Match> seeded =
        MatchStatic({left, right, valid}, points, stereo, config.static_stereo,
                    config.inv_depth_range(), &prediction);
    ASSERT_EQ(seeded.size(), full.size());
    for (std::size_t i = 0; i < full.size(); ++i) {
      EXPECT_EQ(seeded[i].u, full[i].u);
      EXPECT_DOUBLE_EQ(seeded[i].rho, full[i].rho);
    }
  }
}

TEST(StaticStereo, LeftRightCheckDropsInconsistentMatches) {
  const RectifiedStereo stereo = testing::SmallStereo();
  MappingConfig config = Config();
  config.static_stereo.uniqueness = 0.0;
  cv::Mat left = testing::Texture(160, 120, 2);
  cv::Mat right = testing::Shifted(left, 12.0, 0.0);  // d = 12 everywhere
  const cv::Mat valid(120, 160, CV_8UC1, cv::Scalar(255));
  const int u = 100, v = 60, hw = 7, hh = 3;
  const cv::Rect patch_at_u(u - hw, v - hh, 15, 7);
  // The point's true partner (d = 12) is wiped out; a copy of its patch sits at d = 30 instead,
  // and a second copy on the left at u − 25 matches that copy at d' = 5, before d' = 30.
  right(cv::Rect(u - 12 - hw - 3, v - hh - 3, 21, 13)).setTo(128.0f);
  left(patch_at_u).copyTo(right(cv::Rect(u - 30 - hw, v - hh, 15, 7)));
  const cv::Mat copy = left(patch_at_u).clone();
  copy.copyTo(left(cv::Rect(u - 25 - hw, v - hh, 15, 7)));
  std::vector<Eigen::Vector2f> points = {{static_cast<float>(u), static_cast<float>(v)}};
  for (int vv = 20; vv < 100; vv += 9)  // and consistent points elsewhere
    points.emplace_back(40.0f, static_cast<float>(vv));
  const std::vector<Match> without = MatchStatic({left, right, valid}, points, stereo,
                                                 config.static_stereo, config.inv_depth_range());
  ASSERT_FALSE(without.empty());
  EXPECT_EQ(without.front().u, static_cast<float>(u));
  EXPECT_NEAR(stereo.Disparity(without.front().rho), 30.0, 1e-9);  // fooled by the copy
  config.static_stereo.left_right_tolerance_px = 1;
  const std::vector<Match> with = MatchStatic({left, right, valid}, points, stereo,
                                              config.static_stereo, config.inv_depth_range());
  EXPECT_EQ(with.size(), without.size() - 1);
  for (const Match& m : with) {
    EXPECT_NE(m.u, static_cast<float>(u));
    EXPECT_NEAR(stereo.Disparity(m.rho), 12.0, 1e-9);
  }
}

TEST(StaticStereo, DisparityRangeFollowsTheDepthRange) {
  const RectifiedStereo stereo = testing::SmallStereo();
  MappingConfig config = Config();
  const DisparityRange r = StaticDisparityRange(stereo, config.inv_depth_range());
  EXPECT_EQ(r.min, 0);
  EXPECT_EQ(r.max, 81);                 // ⌈321.6 · 0.25⌉
  config.inv_depth_max = 40.0 / 321.6;  // nearest depth 8 m
  EXPECT_EQ(StaticDisparityRange(stereo, config.inv_depth_range()).max, 40);
  config.inv_depth_min = 5.5 / 321.6;  // farthest 58 m
  EXPECT_EQ(StaticDisparityRange(stereo, config.inv_depth_range()).min, 5);
}

TEST(TemporalStereo, TriangulatesAKnownPoint) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const Eigen::Vector3d p_now(1.0, -0.5, 12.0);
  geometry::RigidTransform T_past_now;
  T_past_now.t = {0.1, 0.4, -0.3};
  T_past_now.R = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()).toRotationMatrix();
  double u0, v0, u1, v1;
  ASSERT_TRUE(stereo.Project(p_now, &u0, &v0));
  ASSERT_TRUE(stereo.Project(T_past_now * p_now, &u1, &v1));
  EXPECT_NEAR(TriangulateDepth(stereo, {u0, v0}, {u1, v1}, T_past_now), 12.0, 1e-9);
}

// A fronto-parallel plane at 10 m; the camera moved 0.3 m down (+y) since the past view, so the
// plane appears f·0.3/10 = 16.08 px lower now. Stripes are horizontal (what temporal stereo is
// for), on a texture that makes the match unique unless `bare`.
struct StripedPlane {
  RectifiedStereo stereo = testing::SmallStereo();
  double shift = stereo.f * 0.3 / 10.0;
  cv::Mat aa_now, aa_past;
  geometry::RigidTransform T_past_now;  // p_past = p_now + (0, 0.3, 0): vertical segments
  std::vector<Eigen::Vector2f> points;

  explicit StripedPlane(bool bare = false) {
    aa_now = bare ? cv::Mat(120, 160, CV_32FC1, cv::Scalar(0.0f)) : testing::Texture(160, 120, 3);
    for (int y = 0; y < 120; ++y) {
      if (y % 13 < 2) aa_now.row(y).setTo(255.0f);
    }
    T_past_now.t = {0.0, 0.3, 0.0};
    aa_past = testing::Shifted(aa_now, 0.0, -shift);  // past(y + shift) = now(y)
    for (int v = 30; v < 90; v += 7)
      for (int u = 40; u < 120; u += 13)
        points.emplace_back(u, v);
  }
  std::vector<Match> Matches(const MappingConfig& config) const {
    return MatchTemporal({aa_now, aa_past, T_past_now}, points, stereo, config.temporal_stereo,
                         config.static_stereo.zncc_threshold, config.inv_depth_range());
  }
};

TEST(TemporalStereo, MatchesHorizontalEdgesAlongTheEpipolarSegment) {
  const StripedPlane scene;
  const std::vector<Match> matches = scene.Matches(Config());
  ASSERT_GT(matches.size(), scene.points.size() / 2);
  for (const Match& m : matches) {
    EXPECT_EQ(m.kind, StereoKind::kTemporal);
    EXPECT_NEAR(1.0 / m.rho, 10.0, 10.0 * 0.5 / scene.shift);  // within half a pixel of parallax
  }
}

// With the previous map's plane as prediction, the search covers only the depths near it: a right
// one (10.2 m) gives the full search's matches, and so does one beside the truth (11 m: depths
// 10.3–11.8 m), whose best then lies at the window's near end, searched again over the whole
// segment.
TEST(TemporalStereo, SearchesTheDepthsThePreviousMapPredicts) {
  const StripedPlane scene;
  const MappingConfig config = Config();
  const std::vector<Match> full = scene.Matches(config);
  ASSERT_GT(full.size(), scene.points.size() / 2);
  for (const double predicted_m : {10.2, 11.0}) {
    SCOPED_TRACE(predicted_m);
    const DisparityPrediction prediction(PlaneMap(scene.stereo, scene.stereo.fb() / predicted_m),
                                         {}, scene.stereo);
    const std::vector<Match> seeded =
        MatchTemporal({scene.aa_now, scene.aa_past, scene.T_past_now}, scene.points, scene.stereo,
                      config.temporal_stereo, config.static_stereo.zncc_threshold,
                      config.inv_depth_range(), nullptr, &prediction);
    ASSERT_EQ(seeded.size(), full.size());
    for (std::size_t i = 0; i < full.size(); ++i) {
      EXPECT_EQ(seeded[i].u, full[i].u);
      EXPECT_NEAR(seeded[i].rho, full[i].rho, 1e-12);
    }
  }
}

// The cross-check searches a second, older view (0.6 m away) independently: one consistent with
// the plane at 10 m keeps the matches (and their depth); one showing the structure where a plane
// at 7 m would be rejects every match, though the first partner alone accepts them.
TEST(TemporalStereo, CrossCheckKeepsOnlyDepthsASecondViewConfirms) {
  const StripedPlane scene;
  MappingConfig config = Config();
  const std::size_t unchecked = scene.Matches(config).size();
  ASSERT_GT(unchecked, scene.points.size() / 2);
  config.temporal_stereo.cross_check_px = 1.0;
  geometry::RigidTransform T_check_now;
  T_check_now.t = {0.0, 0.6, 0.0};
  auto checked = [&](double check_depth_m) {
    const cv::Mat aa_check =
        testing::Shifted(scene.aa_now, 0.0, -scene.stereo.f * 0.6 / check_depth_m);
    TemporalStereoInput input{scene.aa_now, scene.aa_past, scene.T_past_now};
    input.aa_check = &aa_check;
    input.T_check_now = &T_check_now;
    return MatchTemporal(input, scene.points, scene.stereo, config.temporal_stereo,
                         config.static_stereo.zncc_threshold, config.inv_depth_range());
  };
  const std::vector<Match> consistent = checked(10.0);
  EXPECT_GE(consistent.size(), unchecked * 9 / 10);
  for (const Match& m : consistent)
    EXPECT_NEAR(1.0 / m.rho, 10.0, 10.0 * 0.5 / scene.shift);
  EXPECT_TRUE(checked(7.0).empty());
}

// Every candidate is counted once, under the test that dropped it (summary.json shows these).
TEST(TemporalStereo, StatsCountWhereEachCandidateIsLost) {
  const StripedPlane scene;
  MappingConfig config = Config();
  auto stats_of = [&](const TemporalStereoInput& input) {
    TemporalMatchStats stats;
    const std::vector<Match> matches =
        MatchTemporal(input, scene.points, scene.stereo, config.temporal_stereo,
                      config.static_stereo.zncc_threshold, config.inv_depth_range(), &stats);
    EXPECT_EQ(stats.matched, static_cast<int>(matches.size()));
    EXPECT_EQ(stats.matched + stats.no_segment + stats.no_match + stats.ill_conditioned +
                  stats.check_rejected + stats.out_of_range,
              static_cast<int>(scene.points.size()));
    return stats;
  };
  const TemporalStereoInput plain{scene.aa_now, scene.aa_past, scene.T_past_now};
  const TemporalMatchStats base = stats_of(plain);
  ASSERT_GT(base.matched, static_cast<int>(scene.points.size()) / 2);
  EXPECT_EQ(base.ill_conditioned + base.check_rejected + base.out_of_range, 0);

  // A short baseline (0.1 m: 5.4 px of parallax at 10 m): one pixel of matching error moves the
  // depth by ~19 %, above a max_relative_depth_error of 0.1, so the matches are ill-conditioned.
  StripedPlane short_baseline;
  short_baseline.T_past_now.t = {0.0, 0.1, 0.0};
  short_baseline.aa_past =
      testing::Shifted(short_baseline.aa_now, 0.0, -short_baseline.stereo.f * 0.1 / 10.0);
  const TemporalStereoInput short_input{short_baseline.aa_now, short_baseline.aa_past,
                                        short_baseline.T_past_now};
  EXPECT_EQ(stats_of(short_input).ill_conditioned, 0);  // the test is off by default
  config.temporal_stereo.max_relative_depth_error = 0.1;
  const TemporalMatchStats strict = stats_of(short_input);
  EXPECT_EQ(strict.matched, 0);
  EXPECT_GT(strict.ill_conditioned, base.matched / 2);
  config = Config();

  // A check partner that puts the plane at 7 m rejects what the first partner matched.
  config.temporal_stereo.cross_check_px = 1.0;
  geometry::RigidTransform T_check_now;
  T_check_now.t = {0.0, 0.6, 0.0};
  const cv::Mat aa_check = testing::Shifted(scene.aa_now, 0.0, -scene.stereo.f * 0.6 / 7.0);
  TemporalStereoInput checked = plain;
  checked.aa_check = &aa_check;
  checked.T_check_now = &T_check_now;
  const TemporalMatchStats rejected = stats_of(checked);
  EXPECT_EQ(rejected.matched, 0);
  EXPECT_EQ(rejected.check_rejected, base.matched);
}

// Why the check partner is not at twice the first baseline (cross_check_spacing): bare stripes
// every 13 px, the plane at 10 m, and a depth range of 5.2-5.9 m that holds only a wrong match.
// The first partner (0.3 m) finds the stripe one period off: 16.08 + 13 px, 5.53 m. A check
// partner at 0.6 m finds the stripe two periods off (32.16 + 26 px): 5.53 m again, so the check
// confirms the wrong depth. At 0.45 m no stripe lies in the range (24.12 + 13 or + 26 px vs.
// 40.9-46.4 px) and every match is rejected.
TEST(TemporalStereo, CrossCheckAtTwiceTheBaselineConfirmsAPeriodicMismatch) {
  const StripedPlane scene(/*bare=*/true);
  MappingConfig config = Config();
  config.inv_depth_min = 1.0 / 5.9;
  config.inv_depth_max = 1.0 / 5.2;
  std::vector<Eigen::Vector2f> on_stripes;  // patches centred on a stripe's first row
  for (int v : {26, 39, 52})
    for (int u = 40; u < 120; u += 20)
      on_stripes.emplace_back(u, v);
  const std::vector<Match> unchecked = MatchTemporal(
      {scene.aa_now, scene.aa_past, scene.T_past_now}, on_stripes, scene.stereo,
      config.temporal_stereo, config.static_stereo.zncc_threshold, config.inv_depth_range());
  ASSERT_EQ(unchecked.size(), on_stripes.size());
  const double alias_m = scene.stereo.f * 0.3 / (scene.shift + 13.0);
  for (const Match& m : unchecked)
    EXPECT_NEAR(1.0 / m.rho, alias_m, 0.05);
  config.temporal_stereo.cross_check_px = 1.0;
  auto checked = [&](double baseline_m) {
    geometry::RigidTransform T_check_now;
    T_check_now.t = {0.0, baseline_m, 0.0};
    const cv::Mat aa_check =
        testing::Shifted(scene.aa_now, 0.0, -scene.stereo.f * baseline_m / 10.0);
    TemporalStereoInput input{scene.aa_now, scene.aa_past, scene.T_past_now};
    input.aa_check = &aa_check;
    input.T_check_now = &T_check_now;
    return MatchTemporal(input, on_stripes, scene.stereo, config.temporal_stereo,
                         config.static_stereo.zncc_threshold, config.inv_depth_range());
  };
  const std::vector<Match> twice = checked(0.6);
  EXPECT_EQ(twice.size(), unchecked.size());
  for (const Match& m : twice)
    EXPECT_NEAR(1.0 / m.rho, alias_m, 0.05);
  EXPECT_TRUE(checked(0.45).empty());
}

TEST(DepthRefinement, RecoversSubPixelDisparityAndItsUncertainty) {
  const RectifiedStereo stereo = testing::SmallStereo();
  const double d = 20.37;
  const cv::Mat left = testing::WaveTexture(160, 120, 4);
  const cv::Mat right = testing::WaveTexture(160, 120, 4, d, 0.0);  // exact sub-pixel shift
  const MappingConfig config = Config();
  std::vector<Match> matches;
  for (int v = 20; v < 100; v += 10)
    for (int u = 50; u < 140; u += 10)
      matches.push_back({static_cast<float>(u), static_cast<float>(v),
                         stereo.InvDepthOfDisparity(20.0), 0.01, StereoKind::kStatic, false});
  const std::vector<DepthPoint> refined =
      RefineDepths({left, right, nullptr, nullptr, {}}, matches, stereo, config.depth_refinement,
                   {}, config.inv_depth_range());
  ASSERT_GT(refined.size(), matches.size() * 9 / 10);
  for (const DepthPoint& p : refined) {
    EXPECT_NEAR(stereo.Disparity(p.rho), d, 0.03);  // bilinear interpolation bias only
    EXPECT_GT(p.variance(), 0.0);
    EXPECT_LT(std::sqrt(p.variance()), 0.01);  // a fraction of a pixel of disparity
  }
}

// depth_refinement.max_relative_stddev culls temporal estimates too; temporal_stereo's
// residual_threshold and max_inv_depth_stddev, the AA residual's, cull them in place of
// depth_refinement's.
TEST(DepthRefinement, TemporalEstimatesAreCulledByTheirOwnThresholds) {
  const StripedPlane scene;
  const std::vector<Match> matches = scene.Matches(Config());
  ASSERT_GT(matches.size(), scene.points.size() / 2);
  const cv::Mat none(120, 160, CV_32FC1, cv::Scalar(0.0f));
  auto refined = [&](const MappingConfig& config) {
    return RefineDepths({none, none, &scene.aa_now, &scene.aa_past, scene.T_past_now}, matches,
                        scene.stereo, config.depth_refinement,
                        {config.temporal_stereo.max_inv_depth_stddev,
                         config.temporal_stereo.residual_threshold},
                        config.inv_depth_range())
        .size();
  };
  const std::size_t all = refined(Config());
  ASSERT_GT(all, matches.size() / 2);
  MappingConfig relative = Config();
  relative.depth_refinement.max_relative_stddev = 1e-6;
  EXPECT_EQ(refined(relative), 0u);
  for (const bool tight_stddev : {false, true}) {
    MappingConfig config = Config();
    (tight_stddev ? config.temporal_stereo.max_inv_depth_stddev
                  : config.temporal_stereo.residual_threshold) = 1e-9;
    EXPECT_EQ(refined(config), 0u) << tight_stddev;
    // A tight refinement threshold does not apply where temporal_stereo has its own.
    (tight_stddev ? config.depth_refinement.max_inv_depth_stddev
                  : config.depth_refinement.residual_threshold) = 1e-9;
    (tight_stddev ? config.temporal_stereo.max_inv_depth_stddev
                  : config.temporal_stereo.residual_threshold) = 1e9;
    EXPECT_EQ(refined(config), all) << tight_stddev;
  }
}

TEST(DepthRefinement, StudentTScaleIgnoresZerosAndShrinksForSmallResiduals) {
  const std::vector<float> small = {1, -1, 2, -2, 0, 0, 1};
  const std::vector<float> large = {40, -30, 50, -60, 0, 35};
  const double s2 = 17.277 * 17.277;
  EXPECT_LT(StudentTScale2(small, 2.182, s2), 10.0);
  EXPECT_GT(StudentTScale2(large, 2.182, s2), StudentTScale2(small, 2.182, s2));
  EXPECT_DOUBLE_EQ(StudentTScale2(std::vector<float>{0, 0}, 2.182, s2), s2);
}

}  // namespace
}  // namespace aavio::mapping
