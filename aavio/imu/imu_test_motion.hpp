#pragma once
/// Test helpers of the IMU tests: an analytic motion of an IMU carrying a camera (hand-held or
/// driving), the IMU readings it gives and tracked camera poses with a registration's noise.

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/geometry/random_draws.hpp"
#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/imu_config.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu::test_motion {

using geometry::ExpSO3;
using geometry::RigidTransform;

// Gravity in the tracking's world, not along an axis (the world is the first camera's frame).
inline const Eigen::Vector3d kGravity =
    ExpSO3(Eigen::Vector3d(0.3, -0.2, 0.1)) * Eigen::Vector3d(0, 0, -9.81);
inline const Eigen::Vector3d kGyroBias(0.004, -0.003, 0.002), kAccelBias(0.05, -0.04, 0.03);
// The camera on the IMU: turned and 8 cm off.
inline const RigidTransform kImuCam(ExpSO3(Eigen::Vector3d(1.2, -0.4, 0.3)),
                             Eigen::Vector3d(0.08, 0.01, -0.03));

// A motion of the IMU: hand-held (turning, ~1 m/s) or driving (10 m/s, a slow turn, bumps).
struct Motion {
  bool driving = false;
  Eigen::Vector3d Phi(double t) const {
    if (driving) return {0.02 * std::sin(2 * t), 0.3 * std::sin(0.3 * t), 0.01 * std::sin(1.7 * t)};
    return {0.3 * std::sin(1.1 * t), -0.4 * std::sin(0.7 * t + 1), 0.5 * std::sin(0.5 * t)};
  }
  Eigen::Vector3d PhiDot(double t) const {
    if (driving)
      return {0.04 * std::cos(2 * t), 0.09 * std::cos(0.3 * t), 0.017 * std::cos(1.7 * t)};
    return {0.33 * std::cos(1.1 * t), -0.28 * std::cos(0.7 * t + 1), 0.25 * std::cos(0.5 * t)};
  }
  Eigen::Matrix3d R(double t) const { return ExpSO3(Phi(t)); }
  Eigen::Vector3d P(double t) const {
    if (driving) return {10 * t, 0.05 * std::sin(3 * t), 2 * std::sin(0.2 * t)};
    return {std::sin(0.8 * t), 0.3 * std::cos(1.3 * t), 0.5 * t + 0.1 * std::sin(2 * t)};
  }
  Eigen::Vector3d V(double t) const {
    if (driving) return {10.0, 0.15 * std::cos(3 * t), 0.4 * std::cos(0.2 * t)};
    return {0.8 * std::cos(0.8 * t), -0.39 * std::sin(1.3 * t), 0.5 + 0.2 * std::cos(2 * t)};
  }
  Eigen::Vector3d A(double t) const {
    if (driving) return {0.0, -0.45 * std::sin(3 * t), -0.08 * std::sin(0.2 * t)};
    return {-0.64 * std::sin(0.8 * t), -0.507 * std::cos(1.3 * t), -0.4 * std::sin(2 * t)};
  }
  RigidTransform WorldCam(double t) const { return RigidTransform(R(t), P(t)) * kImuCam; }
};

inline std::vector<ImuSample> Imu(const Motion& motion, double t_end_s, std::uint64_t seed) {
  const ImuConfig config;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<ImuSample> out;
  for (int k = 0; k <= t_end_s * 1000; ++k) {
    const double t = k / 1000.0;
    const Eigen::Vector3d gyro =
        geometry::RightJacobianSO3(motion.Phi(t)) * motion.PhiDot(t) + kGyroBias +
        config.gyro_noise_density * std::sqrt(1000.0) * geometry::DrawZyx(n, rng);
    const Eigen::Vector3d accel =
        motion.R(t).transpose() * (motion.A(t) - kGravity) + kAccelBias +
        config.accel_noise_density * std::sqrt(1000.0) * geometry::DrawZyx(n, rng);
    out.push_back({SecondsToNs(t), gyro, accel});
  }
  return out;
}

// A tracked camera pose with the registration's few millimetres and tenth of a degree.
inline RigidTransform Tracked(const Motion& motion, double t, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  RigidTransform T = motion.WorldCam(t);
  T.R = T.R * ExpSO3(0.0015 * geometry::DrawZyx(n, rng));
  T.t += 0.003 * geometry::DrawZyx(n, rng);
  return T;
}

}  // namespace aavio::imu::test_motion
