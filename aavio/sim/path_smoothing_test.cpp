#include "aavio/sim/path_smoothing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "aavio/sim/motion_spline.hpp"

namespace aavio::sim {
namespace {

using geometry::ExpSO3;
using geometry::LogSO3;

constexpr double kDeg = M_PI / 180.0;

/// A hand-held-like motion (0.3 m and 30° swings at 0.3–0.7 Hz) sampled at 200 Hz for 8 s, the
/// stamps optionally uneven by up to ±1 ms.
std::vector<geometry::StampedPose> TruePath(bool uneven_stamps) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  std::vector<geometry::StampedPose> poses;
  for (int k = 0; k < 1600; ++k) {
    const double t = 0.005 * k + (uneven_stamps ? jitter(rng) : 0.0);
    const Eigen::Vector3d p(0.3 * std::sin(2 * M_PI * 0.3 * t), 0.1 * std::sin(2 * M_PI * 0.7 * t),
                            0.2 * std::cos(2 * M_PI * 0.4 * t));
    const Eigen::Vector3d w(0.5 * std::sin(2 * M_PI * 0.5 * t), 0.3 * std::cos(2 * M_PI * 0.6 * t),
                            0.2 * std::sin(2 * M_PI * 0.35 * t));
    poses.push_back({1518196259'000000000 + SecondsToNs(t), {ExpSO3(w), p}});
  }
  return poses;
}

std::vector<geometry::StampedPose> Measured(const std::vector<geometry::StampedPose>& truth,
                                            double position_m, double rotation_rad) {
  std::mt19937 rng(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<geometry::StampedPose> measured = truth;
  for (geometry::StampedPose& p : measured) {
    // Per-axis σ = rotation_rad / √3, so the rms angle is rotation_rad.
    const Eigen::Vector3d dw(unit(rng), unit(rng), unit(rng));
    p.T_world_body.R = p.T_world_body.R * ExpSO3(dw * rotation_rad / std::sqrt(3.0));
    p.T_world_body.t += position_m * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
  }
  return measured;
}

struct PathError {
  double position_m = 0, rotation_rad = 0;
};
PathError RmsError(const std::vector<geometry::StampedPose>& a,
                   const std::vector<geometry::StampedPose>& b) {
  PathError e;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e.position_m += (a[i].T_world_body.t - b[i].T_world_body.t).squaredNorm() / 3.0;
    e.rotation_rad += LogSO3(a[i].T_world_body.R.transpose() * b[i].T_world_body.R).squaredNorm();
  }
  e.position_m = std::sqrt(e.position_m / a.size());
  e.rotation_rad = std::sqrt(e.rotation_rad / a.size());
  return e;
}

/// rms of the spline's angular velocity minus the true one [rad/s].
double AngularVelocityJitter(const std::vector<geometry::StampedPose>& truth,
                             const std::vector<geometry::StampedPose>& path) {
  const MotionSpline exact = *MotionSpline::Fit(truth);
  const MotionSpline followed = *MotionSpline::Fit(path);
  double sum = 0.0;
  int n = 0;
  for (TimeNs t = exact.t_begin_ns() + kNsPerS; t < exact.t_end_ns() - kNsPerS; t += 1'000'000) {
    sum += (followed.AngularVelocity(t) - exact.AngularVelocity(t)).squaredNorm();
    ++n;
  }
  return std::sqrt(sum / n);
}

TEST(PathSmoothing, EstimatesTheMeasurementNoiseWithTheMotionCancelled) {
  // Motion-capture-like noise: 0.4 mm per axis and 0.2° of rotation.
  const auto truth = TruePath(false);
  const PathNoise clean = EstimatePathNoise(truth);
  EXPECT_LT(clean.position_m, 1e-6);
  EXPECT_LT(clean.rotation_rad, 1e-3 * kDeg);
  for (const bool uneven : {false, true}) {
    for (const double scale : {0.5, 1.0, 4.0}) {
      const auto measured = Measured(TruePath(uneven), scale * 4e-4, scale * 0.2 * kDeg);
      const PathNoise noise = EstimatePathNoise(measured);
      EXPECT_NEAR(noise.position_m, scale * 4e-4, scale * 4e-4 * 0.1) << scale << uneven;
      EXPECT_NEAR(noise.rotation_rad, scale * 0.2 * kDeg, scale * 0.2 * kDeg * 0.1) << scale;
    }
  }
}

TEST(PathSmoothing, RemovesTheNoiseAndLeavesTheMotion) {
  for (const bool uneven : {false, true}) {
    const auto truth = TruePath(uneven);
    const auto measured = Measured(truth, 4e-4, 0.2 * kDeg);
    Expected<SmoothedPath> smoothed = SmoothRecordedPath(measured);
    ASSERT_TRUE(smoothed.ok()) << smoothed.status().message();
    ASSERT_EQ(smoothed->poses.size(), truth.size());
    // The residual matches the noise it was told, and the path is far closer to the truth
    // than the measurement was.
    EXPECT_NEAR(smoothed->position_residual_m, smoothed->noise.position_m, 0.1 * 4e-4);
    EXPECT_NEAR(smoothed->rotation_residual_rad, smoothed->noise.rotation_rad, 0.02 * kDeg);
    const PathError before = RmsError(measured, truth);
    const PathError after = RmsError(smoothed->poses, truth);
    EXPECT_LT(after.position_m, 0.3 * before.position_m) << uneven;
    EXPECT_LT(after.rotation_rad, 0.3 * before.rotation_rad) << uneven;
    // What the simulated gyroscope would read: the jitter the noise made is mostly gone.
    const double jitter_before = AngularVelocityJitter(truth, measured);
    const double jitter_after = AngularVelocityJitter(truth, smoothed->poses);
    EXPECT_GT(jitter_before, 0.3);  // rad/s, the noise a spline through every sample makes
    EXPECT_LT(jitter_after, 0.1 * jitter_before) << uneven;
  }
}

TEST(PathSmoothing, LeavesANoiseFreePathAlone) {
  const auto truth = TruePath(false);
  Expected<SmoothedPath> smoothed = SmoothRecordedPath(truth);
  ASSERT_TRUE(smoothed.ok());
  const PathError change = RmsError(smoothed->poses, truth);
  EXPECT_LT(change.position_m, 1e-6);
  EXPECT_LT(change.rotation_rad, 1e-3 * kDeg);
}

TEST(PathSmoothing, ShortPathsPassAndUnsortedStampsAreRefused) {
  auto truth = TruePath(false);
  const std::vector<geometry::StampedPose> short_path(truth.begin(), truth.begin() + 3);
  Expected<SmoothedPath> smoothed = SmoothRecordedPath(short_path);
  ASSERT_TRUE(smoothed.ok());
  EXPECT_EQ(smoothed->poses.size(), 3u);
  std::swap(truth[10], truth[11]);
  Expected<SmoothedPath> unsorted = SmoothRecordedPath(truth);
  ASSERT_FALSE(unsorted.ok());
  EXPECT_NE(unsorted.status().message().find("pose 11"), std::string::npos);
}

}  // namespace
}  // namespace aavio::sim
