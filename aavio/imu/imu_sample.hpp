#pragma once
/// One IMU reading, in the IMU frame.

#include <Eigen/Core>

#include "aavio/common/time.hpp"

namespace aavio::imu {

/// Gravity's magnitude the IMU code assumes [m/s²].
inline constexpr double kGravityMS2 = 9.81;

struct ImuSample {
  TimeNs t_ns = 0;
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();  ///< angular velocity
  Eigen::Vector3d accel_m_s2 = Eigen::Vector3d::Zero();  ///< specific force (gravity included)
};

}  // namespace aavio::imu
