#include "aavio/imu/gyro_bias_estimator.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "aavio/geometry/random_draws.hpp"
#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/gyro_preintegration.hpp"

namespace aavio::imu {
namespace {

// Readings of ω(t) + bias + white noise at 1 kHz over [0, duration].
std::vector<ImuSample> Readings(const std::function<Eigen::Vector3d(double)>& omega,
                                const Eigen::Vector3d& bias, double noise, double duration_s,
                                std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  std::vector<ImuSample> out;
  for (TimeNs t = 0; t <= SecondsToNs(duration_s); t += kNsPerMs) {
    const Eigen::Vector3d w = omega(NsToSeconds(t)) + bias + geometry::DrawZyx(n, rng);
    out.push_back({t, w, Eigen::Vector3d::Zero()});
  }
  return out;
}

TEST(GyroBiasEstimator, StaticInitTakesTheMeanOfAStillInterval) {
  ImuConfig config;
  config.bias_mode = GyroBiasMode::kStaticInit;
  config.static_init_s = 1.0;
  const Eigen::Vector3d bias(0.002, -0.001, 0.0015);
  const auto samples =
      Readings([](double) { return Eigen::Vector3d::Zero(); }, bias, 0.005, 2.0, 1);
  GyroBiasEstimator estimator(config, 0);
  EXPECT_FALSE(estimator.static_init_done());
  estimator.AddSamples(samples);
  ASSERT_TRUE(estimator.static_init_done());
  EXPECT_TRUE(estimator.static_init_accepted());
  EXPECT_LT((estimator.bias() - bias).norm(), 5e-4);  // σ/√1000 per axis ≈ 1.6e-4
}

TEST(GyroBiasEstimator, StaticInitRefusesAMovingStart) {
  ImuConfig config;
  config.bias_mode = GyroBiasMode::kStaticInit;
  config.gyro_bias_rad_s = {0.001, 0.0, 0.0};
  const auto samples =
      Readings([](double t) { return Eigen::Vector3d(0.0, 0.5 * std::sin(6.0 * t), 0.0); },
               Eigen::Vector3d(0.002, 0.0, 0.0), 0.005, 2.0, 2);
  GyroBiasEstimator estimator(config, 0);
  estimator.AddSamples(samples);
  ASSERT_TRUE(estimator.static_init_done());
  EXPECT_FALSE(estimator.static_init_accepted());
  EXPECT_EQ(estimator.bias(), Eigen::Vector3d(0.001, 0.0, 0.0));  // the configured value stays
}

// Online: the tracker measures the true pose at each 10 ms tick with an absolute error of 0.05°
// (tracked rotations telescope over the window); over 6 s the estimate converges.
TEST(GyroBiasEstimator, OnlineRecoversTheBiasFromTrackedRotations) {
  ImuConfig config;
  config.bias_mode = GyroBiasMode::kOnline;
  config.online_window = 20;
  const Eigen::Vector3d bias(0.01, -0.02, 0.015);
  auto omega = [](double t) { return Eigen::Vector3d(0.3 * std::sin(t), 0.8, -0.2 * t); };
  const auto samples = Readings(omega, bias, 0.0, 6.0, 3);
  const auto truth = Readings(omega, Eigen::Vector3d::Zero(), 0.0, 6.0, 3);
  GyroBiasEstimator estimator(config, 0);
  std::mt19937 rng(4);
  std::normal_distribution<double> pose_noise(0.0, 0.05 * M_PI / 180.0 / std::sqrt(3.0));
  const TimeNs tick = 10 * kNsPerMs;
  Eigen::Matrix3d error_prev = Eigen::Matrix3d::Identity();
  for (TimeNs t = 0; t + tick <= SecondsToNs(6.0); t += tick) {
    const Eigen::Matrix3d error = geometry::ExpSO3(geometry::DrawZyx(pose_noise, rng));
    const Eigen::Matrix3d tracked = error_prev.transpose() *
                                    *IntegrateGyro(truth, t, t + tick, Eigen::Vector3d::Zero()) *
                                    error;
    error_prev = error;
    estimator.AddTrackedTick(samples, t, t + tick, tracked, t > 0);
  }
  EXPECT_LT((estimator.bias() - bias).norm(), 2e-3) << estimator.bias().transpose();
}

TEST(GyroBiasEstimator, FixedModeNeverChanges) {
  ImuConfig config;
  config.gyro_bias_rad_s = {0.0, 0.003, 0.0};
  GyroBiasEstimator estimator(config, 0);
  const std::vector<ImuSample> samples = {
      {0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()},
      {kNsPerMs * 20, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
  for (int i = 0; i < 30; ++i)
    estimator.AddTrackedTick(samples, 0, 10 * kNsPerMs,
                             geometry::ExpSO3(Eigen::Vector3d(0.001, 0, 0)), true);
  EXPECT_EQ(estimator.bias(), Eigen::Vector3d(0.0, 0.003, 0.0));
}

}  // namespace
}  // namespace aavio::imu
