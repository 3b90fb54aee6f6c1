#include "aavio/sim/imu_synthesis.hpp"

#include <gtest/gtest.h>

namespace aavio::sim {
namespace {

using geometry::ExpSO3;
using geometry::LogSO3;

MotionSpline Wavy(double duration_s) {
  std::vector<geometry::StampedPose> poses;
  for (double t = 0.0; t <= duration_s + 1e-9; t += 0.01) {
    poses.push_back({SecondsToNs(t),
                     {ExpSO3(Eigen::Vector3d(0.6 * std::sin(1.3 * t), 0.8 * std::sin(0.9 * t),
                                             1.2 * std::sin(0.5 * t))),
                      Eigen::Vector3d(std::sin(t), std::cos(0.7 * t), 0.1 * t)}});
  }
  return *MotionSpline::Fit(poses);
}

TEST(ImuSynthesis, IntegratingTheGyroscopeGivesBackTheRotation) {
  const MotionSpline spline = Wavy(5.0);
  // A rotated IMU: readings are in its own frame, ω_imu = R_imu_body ω_body.
  const geometry::RigidTransform T_imu_body(ExpSO3(Eigen::Vector3d(0.1, -2.0, 0.3)),
                                            Eigen::Vector3d::Zero());
  auto samples = SynthesizeImu(spline, T_imu_body, {0, 0, -9.81}, ImuNoiseModel::Perfect(), 1);
  ASSERT_TRUE(samples.ok());
  ASSERT_EQ(samples->size(), 5001u);       // 1 kHz over 5 s, both ends
  Eigen::Matrix3d R = spline.Rotation(0);  // world ← body
  const Eigen::Matrix3d R_body_imu = T_imu_body.R.transpose();
  for (std::size_t k = 0; k + 1 < samples->size(); ++k) {
    const double dt = NsToSeconds((*samples)[k + 1].t_ns - (*samples)[k].t_ns);
    const Eigen::Vector3d w_mid = 0.5 * ((*samples)[k].gyro_rad_s + (*samples)[k + 1].gyro_rad_s);
    R = R * ExpSO3(R_body_imu * w_mid * dt);  // mid-point integration
  }
  EXPECT_LT(geometry::RotationDistance(R, spline.Rotation(spline.t_end_ns())), 1e-4);
}

TEST(ImuSynthesis, AccelerometerAtRestReadsGravity) {
  const geometry::RigidTransform T_world_body(ExpSO3(Eigen::Vector3d(0.3, 0.2, 1.0)),
                                              Eigen::Vector3d(1, 2, 3));
  const MotionSpline still = *MotionSpline::Fit({{0, T_world_body}, {kNsPerS, T_world_body}});
  auto samples = SynthesizeImu(still, {}, {0, 0, -9.81}, ImuNoiseModel::Perfect(), 1);
  ASSERT_TRUE(samples.ok());
  for (const imu::ImuSample& s : *samples) {
    // At rest the accelerometer feels the support force: +9.81 m/s² "up", in the body frame.
    EXPECT_LT((s.accel_m_s2 - T_world_body.R.transpose() * Eigen::Vector3d(0, 0, 9.81)).norm(),
              1e-9);
    EXPECT_LT(s.gyro_rad_s.norm(), 1e-9);
  }
}

TEST(ImuSynthesis, LeverArmAddsCentripetalAcceleration) {
  // Spinning about z at 2 rad/s with the IMU 0.5 m off the axis: |a| = ω² r = 2 m/s² inwards.
  std::vector<geometry::StampedPose> poses;
  for (double t = 0.0; t <= 2.0 + 1e-9; t += 0.005) {
    poses.push_back(
        {SecondsToNs(t), {ExpSO3(Eigen::Vector3d(0, 0, 2.0 * t)), Eigen::Vector3d::Zero()}});
  }
  const MotionSpline spin = *MotionSpline::Fit(poses);
  const geometry::RigidTransform T_imu_body(Eigen::Matrix3d::Identity(),
                                            Eigen::Vector3d(-0.5, 0, 0));
  auto samples = SynthesizeImu(spin, T_imu_body, {0, 0, 0}, ImuNoiseModel::Perfect(), 1);
  const imu::ImuSample& mid = (*samples)[1000];
  EXPECT_NEAR(mid.accel_m_s2.x(), -2.0, 1e-3);  // towards the axis
  EXPECT_NEAR(mid.gyro_rad_s.z(), 2.0, 1e-6);
}

TEST(ImuSynthesis, NoiseHasTheConfiguredDensityAndIsSeeded) {
  std::vector<geometry::StampedPose> still = {{0, {}}, {10 * kNsPerS, {}}};
  const MotionSpline spline = *MotionSpline::Fit(still);
  ImuNoiseModel model = ImuNoiseModel::Perfect();
  model.gyro_noise_density = 0.003;
  model.accel_noise_density = 0.04;
  auto a = SynthesizeImu(spline, {}, {0, 0, 0}, model, 42);
  auto b = SynthesizeImu(spline, {}, {0, 0, 0}, model, 42);
  auto c = SynthesizeImu(spline, {}, {0, 0, 0}, model, 43);
  double gyro_sq = 0.0, accel_sq = 0.0;
  for (const imu::ImuSample& s : *a) {
    gyro_sq += s.gyro_rad_s.squaredNorm();
    accel_sq += s.accel_m_s2.squaredNorm();
  }
  const double n = 3.0 * static_cast<double>(a->size());
  EXPECT_NEAR(std::sqrt(gyro_sq / n), 0.003 * std::sqrt(1000.0), 0.003 * std::sqrt(1000.0) * 0.02);
  EXPECT_NEAR(std::sqrt(accel_sq / n), 0.04 * std::sqrt(1000.0), 0.04 * std::sqrt(1000.0) * 0.02);
  EXPECT_EQ((*a)[777].gyro_rad_s, (*b)[777].gyro_rad_s);  // same seed, same bytes
  EXPECT_NE((*a)[777].gyro_rad_s, (*c)[777].gyro_rad_s);
}

TEST(ImuSynthesis, BiasRandomWalkGrowsLikeTheSquareRootOfTime) {
  std::vector<geometry::StampedPose> still = {{0, {}}, {20 * kNsPerS, {}}};
  const MotionSpline spline = *MotionSpline::Fit(still);
  ImuNoiseModel model = ImuNoiseModel::Perfect();
  model.rate_hz = 100.0;  // the walk's statistics do not depend on the rate
  model.gyro_random_walk = 1e-3;
  // Over many seeds, the bias after T seconds has std walk · √T.
  double sq = 0.0;
  const int runs = 400;
  for (int seed = 0; seed < runs; ++seed) {
    auto s = SynthesizeImu(spline, {}, {0, 0, 0}, model, static_cast<std::uint64_t>(seed));
    sq += s->back().gyro_rad_s.squaredNorm() / 3.0;
  }
  EXPECT_NEAR(std::sqrt(sq / runs), 1e-3 * std::sqrt(20.0), 1e-3 * std::sqrt(20.0) * 0.1);
}

TEST(ImuSynthesis, DatasheetAndPerfectModels) {
  EXPECT_DOUBLE_EQ(ImuNoiseModel().gyro_noise_density, 0.00292);
  const ImuNoiseModel datasheet = ImuNoiseModel::Datasheet();
  EXPECT_NEAR(datasheet.gyro_noise_density, 8.73e-5, 1e-7);   // 0.005 °/s/√Hz
  EXPECT_NEAR(datasheet.accel_noise_density, 3.92e-3, 1e-5);  // 400 µg/√Hz
  EXPECT_EQ(datasheet.gyro_bias, ImuNoiseModel().gyro_bias);
  EXPECT_DOUBLE_EQ(ImuNoiseModel::Perfect().gyro_noise_density, 0.0);
  ImuNoiseModel absurd;
  absurd.gyro_bias[1] = 3.0;  // rad/s
  EXPECT_FALSE(absurd.Validate().ok());
}

}  // namespace
}  // namespace aavio::sim
