#include "aavio/eval/relative_error.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "aavio/eval/error_statistics.hpp"

namespace aavio::eval {
namespace {

// Ground truth: 10 m straight along x, a pose every 10 cm; `make_est` gives the estimate at s [m].
template <typename F>
std::vector<PosePair> Straight(F make_est) {
  std::vector<PosePair> pairs;
  for (int i = 0; i <= 100; ++i) {
    const double s = 0.1 * i;
    geometry::RigidTransform gt;
    gt.t = {s, 0.0, 0.0};
    pairs.push_back({i * 50'000'000LL, make_est(s, gt), gt});
  }
  return pairs;
}

TEST(RelativeError, StatisticsAsNumpyComputesThem) {
  const ErrorStatistics s = ComputeStatistics({1.0, 2.0, 3.0, 6.0});
  EXPECT_EQ(s.samples, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(50.0 / 4.0));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(14.0 / 4.0));
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 6.0);
  EXPECT_EQ(ComputeStatistics({}).samples, 0u);
}

TEST(RelativeError, ExactEstimateHasNoErrorAndLengthsAreFractionsOfThePath) {
  const auto pairs = Straight([](double, const geometry::RigidTransform& gt) { return gt; });
  const RelativeError r = ComputeRelativeError(pairs, 10.0, 1.0, RelativeErrorConfig{});
  ASSERT_EQ(r.per_length.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_DOUBLE_EQ(r.per_length[k].length_m, 1.0 + static_cast<double>(k));
    EXPECT_GE(r.per_length[k].trans_m.size(), 91u - 10 * k);
    EXPECT_LT(r.per_length[k].trans_m_stats.max, 1e-12);
  }
  EXPECT_LT(r.trans_pct_rmse, 1e-10);
  EXPECT_LT(r.rot_deg_per_m_rmse, 1e-10);
}

TEST(RelativeError, HandComputedScaleAndYawDrift) {
  // 2 % too long everywhere: every sub-trajectory of length L is 0.02 L off, 2 % of L.
  const auto longer = Straight([](double s, const geometry::RigidTransform&) {
    geometry::RigidTransform T;
    T.t = {1.02 * s, 0.0, 0.0};
    return T;
  });
  const RelativeError r = ComputeRelativeError(longer, 10.0, 1.0, RelativeErrorConfig{});
  for (const SubTrajectoryErrors& s : r.per_length) {
    for (std::size_t k = 0; k < s.trans_pct.size(); ++k) {
      // Near the end the closest end pose is short of L (within 20 %); the error is still
      // divided by the nominal L, as rpg does: 2 % of the distance actually travelled / L.
      const double travelled = std::min(s.length_m, 10.0 - s.start_distance_m[k]);
      EXPECT_NEAR(s.trans_pct[k], 2.0 * travelled / s.length_m, 1e-9);
    }
    EXPECT_NEAR(s.trans_pct_stats.max, 2.0, 1e-9);
    EXPECT_NEAR(s.rot_deg_stats.max, 0.0, 1e-9);
  }
  EXPECT_NEAR(r.trans_pct_rmse, 2.0, 0.02);
  // The alignment's scale is applied to the estimate's relative motion: sim3 undoes it.
  EXPECT_NEAR(ComputeRelativeError(longer, 10.0, 1.0 / 1.02, RelativeErrorConfig{}).trans_pct_rmse,
              0.0, 1e-9);
  // The heading drifts 0.5°/m about z, positions exact: rotation 0.5 °/m, yaw 0.5·L degrees.
  const auto drifting = Straight([](double s, const geometry::RigidTransform& gt) {
    geometry::RigidTransform T = gt;
    T.R = Eigen::AngleAxisd(0.5 * s * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  });
  RelativeErrorConfig fixed;
  fixed.lengths_m = {2.0, 4.0};
  const RelativeError d = ComputeRelativeError(drifting, 10.0, 1.0, fixed);
  ASSERT_EQ(d.per_length.size(), 2u);
  EXPECT_NEAR(d.per_length[0].rot_deg_per_m_stats.max, 0.5, 1e-6);
  EXPECT_NEAR(d.per_length[0].rot_deg_per_m_stats.median, 0.5, 1e-6);
  EXPECT_NEAR(d.per_length[1].yaw_deg_stats.median, 2.0, 1e-6);
  EXPECT_NEAR(d.rot_deg_per_m_rmse, 0.5, 0.01);
}

TEST(RelativeError, EndPoseMustBeWithinTwentyPercentOfTheLength) {
  // Two clusters 5 m apart and nothing between: a 2.5 m sub-trajectory has no end within 0.5 m.
  std::vector<PosePair> pairs;
  for (int i = 0; i < 10; ++i) {
    geometry::RigidTransform T;
    T.t = {0.01 * i + (i >= 5 ? 5.0 : 0.0), 0.0, 0.0};
    pairs.push_back({i * 1'000'000LL, T, T});
  }
  RelativeErrorConfig config;
  config.lengths_m = {2.5, 5.0};
  const RelativeError r = ComputeRelativeError(pairs, 5.04, 1.0, config);
  EXPECT_TRUE(r.per_length[0].trans_m.empty());
  EXPECT_EQ(r.per_length[1].trans_m.size(), 5u);
  RelativeErrorConfig bad;
  bad.fractions = {1.5};
  EXPECT_FALSE(bad.Validate().ok());
}

}  // namespace
}  // namespace aavio::eval
