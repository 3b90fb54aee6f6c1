#include "aavio/imu/gyro_preintegration.hpp"

#include <gtest/gtest.h>

#include "aavio/geometry/rotation.hpp"

namespace aavio::imu {
namespace {

std::vector<ImuSample> ConstantRate(const Eigen::Vector3d& w, TimeNs t0, TimeNs t1, TimeNs step) {
  std::vector<ImuSample> samples;
  for (TimeNs t = t0; t <= t1; t += step)
    samples.push_back({t, w, Eigen::Vector3d::Zero()});
  return samples;
}

TEST(GyroPreintegration, ConstantRateGivesTheClosedFormRotation) {
  const Eigen::Vector3d w(0.3, -1.2, 0.5), bias(0.01, 0.02, -0.03);
  const auto samples = ConstantRate(w + bias, 0, 100 * kNsPerMs, kNsPerMs);
  // A tick interval that does not fall on sample stamps: [10.4 ms, 20.7 ms].
  const TimeNs a = 10'400'000, b = 20'700'000;
  const Eigen::Matrix3d R = *IntegrateGyro(samples, a, b, bias);
  const Eigen::Matrix3d expected = geometry::ExpSO3(w * NsToSeconds(b - a));
  EXPECT_LT((R - expected).norm(), 1e-12);
}

TEST(GyroPreintegration, TimeVaryingRateAndRefusedGaps) {
  // ω(t) = (0, 0, α t): rotation about z by α t²/2 — mid-point integration is exact for linear ω.
  std::vector<ImuSample> samples;
  const double alpha = 4.0;
  for (TimeNs t = 0; t <= 50 * kNsPerMs; t += kNsPerMs)
    samples.push_back({t, Eigen::Vector3d(0, 0, alpha * NsToSeconds(t)), Eigen::Vector3d::Zero()});
  const Eigen::Matrix3d R = *IntegrateGyro(samples, 0, 50 * kNsPerMs, Eigen::Vector3d::Zero());
  EXPECT_NEAR(geometry::LogSO3(R).z(), alpha * 0.05 * 0.05 / 2.0, 1e-12);
  EXPECT_FALSE(IntegrateGyro(samples, 0, 60 * kNsPerMs, Eigen::Vector3d::Zero()).ok());
}

// The convention with a synthetic rotation: the IMU is mounted rotated against the camera; a
// camera that turns about its own y axis must be predicted to turn about its y axis.
TEST(GyroPreintegration, ImuRotationExpressedInTheCamera) {
  const Eigen::Matrix3d R_imu_cam = geometry::ExpSO3(Eigen::Vector3d(0.4, -0.7, 1.1));
  const Eigen::Vector3d w_cam(0.0, 0.8, 0.0);
  const Eigen::Vector3d w_imu = R_imu_cam * w_cam;  // the gyroscope measures in its own frame
  const auto samples = ConstantRate(w_imu, 0, 20 * kNsPerMs, kNsPerMs);
  const Eigen::Matrix3d dR_imu = *IntegrateGyro(samples, 0, 10 * kNsPerMs, Eigen::Vector3d::Zero());
  const Eigen::Matrix3d dR_cam = ImuToCameraRotation(dR_imu, R_imu_cam);
  EXPECT_LT((geometry::LogSO3(dR_cam) - w_cam * 0.01).norm(), 1e-12);
  // DSEC's diag(−1, −1, 1) is its own inverse: the ESVO2 convention bug is silent there.
  const Eigen::Matrix3d dsec = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  EXPECT_LT(
      (ImuToCameraRotation(dR_imu, dsec) - ImuToCameraRotation(dR_imu, dsec.transpose())).norm(),
      1e-15);
}

TEST(GyroPreintegration, MeanGyroOfAStaticInterval) {
  const auto samples = ConstantRate(Eigen::Vector3d(0.01, -0.02, 0.005), 0, kNsPerS, kNsPerMs);
  EXPECT_LT((*MeanGyro(samples, 0, kNsPerS) - Eigen::Vector3d(0.01, -0.02, 0.005)).norm(), 1e-15);
  EXPECT_FALSE(MeanGyro(samples, 2 * kNsPerS, 3 * kNsPerS).ok());
}

}  // namespace
}  // namespace aavio::imu
