#include "aavio/imu/motion_evidence.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace aavio::imu {
namespace {

/// 1 kHz samples for `seconds`: a still MEMS IMU (bias 1.2 °/s and 0.3 m/s², white noise as an
/// MPU-6150's) plus the given rate and acceleration.
std::vector<ImuSample> Samples(TimeNs t0, double seconds, const Eigen::Vector3d& rate,
                               const Eigen::Vector3d& acceleration) {
  std::mt19937 rng(3);
  std::normal_distribution<double> gyro_noise(0.0, 0.092), accel_noise(0.0, 1.4);
  std::vector<ImuSample> out;
  for (int k = 0; k < static_cast<int>(seconds * 1000); ++k) {
    ImuSample s;
    s.t_ns = t0 + k * 1'000'000;
    s.gyro_rad_s = Eigen::Vector3d(0.02, -0.015, 0.025) + rate +
                   Eigen::Vector3d(gyro_noise(rng), gyro_noise(rng), gyro_noise(rng));
    s.accel_m_s2 = Eigen::Vector3d(0.2, 9.81 - 0.25, 0.15) + acceleration +
                   Eigen::Vector3d(accel_noise(rng), accel_noise(rng), accel_noise(rng));
    out.push_back(s);
  }
  return out;
}

TEST(MotionEvidence, StillIsNotMovingAndTurningOrAcceleratingIs) {
  MotionEvidence evidence;
  EXPECT_FALSE(evidence.Moving());  // no samples
  evidence.Add(Samples(0, 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  EXPECT_FALSE(evidence.Moving());
  // Turning at 10 °/s: seen once the window holds it.
  evidence.Add(Samples(1'000'000'000, 0.1, {0, 0.17, 0}, Eigen::Vector3d::Zero()));
  EXPECT_TRUE(evidence.Moving());
  // Still again: forgotten after 0.1 s.
  evidence.Add(Samples(1'100'000'000, 0.2, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  EXPECT_FALSE(evidence.Moving());
  // Accelerating upwards at 1.5 m/s² without turning (a drone climbing; y is down).
  evidence.Add(Samples(1'300'000'000, 0.1, Eigen::Vector3d::Zero(), {0, 1.5, 0}));
  EXPECT_TRUE(evidence.Moving());
  // Samples out of order or repeated are skipped, not counted twice.
  evidence.Add(Samples(1'300'000'000, 0.1, {0, 5.0, 0}, Eigen::Vector3d::Zero()));
  evidence.Add(Samples(1'400'000'000, 0.1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  EXPECT_FALSE(evidence.Moving());
}

}  // namespace
}  // namespace aavio::imu
