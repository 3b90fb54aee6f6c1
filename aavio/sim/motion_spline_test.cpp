#include "aavio/sim/motion_spline.hpp"

#include <gtest/gtest.h>

#include <random>

namespace aavio::sim {
namespace {

using geometry::ExpSO3;
using geometry::LogSO3;

/// A hand-held-like 6-DoF path: smooth rotations and translations, sampled at `rate_hz`.
std::vector<geometry::StampedPose> WavyPath(double rate_hz, double duration_s, TimeNs t0_ns) {
  std::vector<geometry::StampedPose> poses;
  for (double t = 0.0; t <= duration_s + 1e-9; t += 1.0 / rate_hz) {
    geometry::StampedPose p;
    p.t_ns = t0_ns + SecondsToNs(t);
    p.T_world_body.R = ExpSO3(Eigen::Vector3d(0.3 * std::sin(1.3 * t), 0.5 * std::sin(0.7 * t + 1),
                                              0.4 * std::cos(1.1 * t)));
    p.T_world_body.t = Eigen::Vector3d(std::sin(t), 0.5 * std::cos(1.5 * t), 0.2 * t);
    poses.push_back(p);
  }
  return poses;
}

TEST(MotionSpline, PassesThroughThePoses) {
  for (double rate : {200.0, 5.0}) {  // mocap-like and DSEC-like pose rates
    const auto poses = WavyPath(rate, 4.0, 1518196259772284031LL);
    Expected<MotionSpline> spline = MotionSpline::Fit(poses);
    ASSERT_TRUE(spline.ok()) << spline.status().message();
    for (const auto& p : poses) {
      EXPECT_LT((spline->Position(p.t_ns) - p.T_world_body.t).norm(), 1e-9) << rate;
    }
    EXPECT_LT(spline->max_fit_error_rad(), rate > 100 ? 1e-6 : 2e-3) << rate;
  }
}

TEST(MotionSpline, DerivativesMatchFiniteDifferences) {
  const auto poses = WavyPath(50.0, 4.0, 0);
  const MotionSpline spline = *MotionSpline::Fit(poses);
  const TimeNs h = 10'000;  // 10 µs
  std::mt19937 rng(3);
  std::uniform_int_distribution<TimeNs> when(SecondsToNs(0.2), SecondsToNs(3.8));
  for (int k = 0; k < 200; ++k) {
    const TimeNs t = when(rng);
    const Eigen::Vector3d v =
        (spline.Position(t + h) - spline.Position(t - h)) / NsToSeconds(2 * h);
    EXPECT_LT((spline.LinearVelocity(t) - v).norm(), 1e-6);
    const Eigen::Vector3d a =
        (spline.LinearVelocity(t + h) - spline.LinearVelocity(t - h)) / NsToSeconds(2 * h);
    EXPECT_LT((spline.LinearAcceleration(t) - a).norm(), 1e-5);
    // Body angular velocity: Log(R(t−h)ᵀ R(t+h)) / 2h.
    const Eigen::Vector3d w =
        LogSO3(spline.Rotation(t - h).transpose() * spline.Rotation(t + h)) / NsToSeconds(2 * h);
    EXPECT_LT((spline.AngularVelocity(t) - w).norm(), 1e-5);
  }
}

TEST(MotionSpline, IsC2AcrossKnots) {
  const auto poses = WavyPath(20.0, 3.0, 0);
  const MotionSpline spline = *MotionSpline::Fit(poses);
  for (std::size_t i = 1; i + 1 < poses.size(); ++i) {
    const TimeNs t = poses[i].t_ns;
    EXPECT_LT((spline.LinearAcceleration(t - 1) - spline.LinearAcceleration(t + 1)).norm(), 1e-6);
    EXPECT_LT((spline.AngularVelocity(t - 1) - spline.AngularVelocity(t + 1)).norm(), 1e-6);
  }
}

TEST(MotionSpline, RefusesTooFewOrUnsortedPoses) {
  auto poses = WavyPath(10.0, 1.0, 0);
  EXPECT_FALSE(MotionSpline::Fit({poses[0]}).ok());
  std::swap(poses[3], poses[4]);
  EXPECT_NE(MotionSpline::Fit(poses).status().message().find("increase strictly"),
            std::string::npos);
}

}  // namespace
}  // namespace aavio::sim
