#pragma once
/// IMU readings from a motion spline (issue 4): gyroscope and accelerometer at the sensor rate,
/// in the IMU frame through the IMU–camera extrinsic, gravity included, with white noise,
/// a constant initial bias and a bias random walk (the continuous-time model of Kalibr/Basalt:
/// discrete white-noise std = density · √rate, random-walk step std = walk density / √rate).

#include <array>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/imu/imu_sample.hpp"
#include "aavio/sim/motion_spline.hpp"

namespace aavio::sim {

/// Defaults: a consumer MEMS IMU (the figures ESVO2's back-end uses for DAVIS/DSEC IMUs).
struct ImuNoiseModel {
  double rate_hz = 1000.0;
  double gyro_noise_density = 0.00292;                     ///< rad/s/√Hz
  double accel_noise_density = 0.04401;                    ///< m/s²/√Hz
  double gyro_random_walk = 3.216e-5;                      ///< rad/s²/√Hz
  double accel_random_walk = 7.658e-4;                     ///< m/s³/√Hz
  std::array<double, 3> gyro_bias{0.002, -0.001, 0.0015};  ///< initial bias [rad/s]
  std::array<double, 3> accel_bias{0.02, -0.03, 0.01};     ///< initial bias [m/s²]

  /// A perfect IMU (no noise, no bias), for tests and for isolating other errors.
  static ImuNoiseModel Perfect();
  /// White noise of the InvenSense MPU-6050/6150 datasheet (the DAVIS240C's IMU): gyroscope
  /// 0.005 °/s/√Hz, accelerometer 400 µg/√Hz — ~30× and ~11× below the defaults, which are an
  /// estimator's inflated tuning rather than the sensor's own noise. Walks and biases as default.
  static ImuNoiseModel Datasheet();
  template <typename V>
  void VisitFields(V&& v) {
    v("rate_hz", rate_hz);
    v("gyro_noise_density", gyro_noise_density);
    v("accel_noise_density", accel_noise_density);
    v("gyro_random_walk", gyro_random_walk);
    v("accel_random_walk", accel_random_walk);
    v("gyro_bias", gyro_bias);
    v("accel_bias", accel_bias);
  }
  Status Validate() const;
};

/// Samples from t_begin to t_end (inclusive of t_begin, every 1/rate). The spline is the pose of
/// the body (camera) in the world; T_imu_body places the IMU (p_imu = T_imu_body · p_body);
/// gravity_world is the gravity vector in the world frame (e.g. (0, 0, −9.81) for z up).
/// Deterministic for a seed.
Expected<std::vector<imu::ImuSample>> SynthesizeImu(const MotionSpline& spline,
                                                    const geometry::RigidTransform& T_imu_body,
                                                    const Eigen::Vector3d& gravity_world,
                                                    const ImuNoiseModel& model, std::uint64_t seed);

}  // namespace aavio::sim
