#pragma once
/// Configuration of the IMU's use (docs/tracking.md): none, the gyroscope prior of the
/// paper, or the full back-end (velocity, biases and gravity estimated; 6-DoF prediction; the
/// IMU alone through stretches without events). The IMU–camera extrinsic is part of the
/// calibration (StereoRig::T_imu_left), not of this config.

#include <array>
#include <utility>

#include "aavio/common/config_fields.hpp"

namespace aavio::imu {

enum class ImuMode {
  kOff,   ///< no IMU: constant-velocity prediction (ESVO)
  kGyro,  ///< the gyroscope's rotation starts each registration [paper]
  kFull,  ///< + the back-end: velocity, both biases and gravity; full 6-DoF prediction; IMU-only
          ///< bridging of event-less stretches (as ESVO2 goes beyond the paper)
};

enum class GyroBiasMode {
  kFixed,       ///< gyro_bias_rad_s as configured [paper: "initialised empirically, not updated"]
  kStaticInit,  ///< mean gyro reading over an initial static interval
  kOnline,      ///< re-estimated from tracked vs pre-integrated rotations (as ESVO2 does)
};

struct ImuConfig {
  ImuMode mode = ImuMode::kGyro;
  GyroBiasMode bias_mode = GyroBiasMode::kFixed;
  std::array<double, 3> gyro_bias_rad_s{0.0, 0.0, 0.0};  ///< in the IMU frame ([ICRA] zero)
  double static_init_s = 1.0;  ///< length of the static interval for static_init [s]
  /// static_init accepts the interval only if no axis' readings have a larger std [rad/s]
  double static_max_std_rad_s = 0.02;
  int online_window = 20;  ///< consecutive tracked ticks in the online estimate's window
  /// online: a re-estimate further than this from the current bias is a tracking failure [rad/s]
  double online_max_rate_rad_s = 0.05;
  double online_gain = 0.2;  ///< online: weight of a new window's estimate once warmed up
  // full mode: the back-end.
  double gyro_noise_density = 0.00292;  ///< rad/s/√Hz (Kalibr's gyroscope_noise_density)
  double accel_noise_density = 0.044;   ///< m/s²/√Hz (Kalibr's accelerometer_noise_density)
  /// The longest stretch without events carried on the IMU alone before tracking is lost
  /// (a standstill the IMU sees as such has no limit) [s].
  double max_bridge_s = 2.0;
  /// IMU clock minus camera clock: t_imu = t_cam + time_offset_s (Kalibr's timeshift_cam_imu).
  double time_offset_s = 0.0;

  template <typename V>
  void VisitFields(V&& v) {
    v("mode", mode, "off (no IMU), gyro (gyroscope prior: the paper) or full (6-DoF IMU back-end)");
    v("bias_mode", bias_mode, "gyroscope bias: fixed (gyro_bias_rad_s), static_init or online");
    v("gyro_bias_rad_s", gyro_bias_rad_s, "gyroscope bias in the IMU frame [rad/s]");
    v("static_init_s", static_init_s, "static_init: length of the initial still interval [s]");
    v("static_max_std_rad_s", static_max_std_rad_s,
      "static_init: accepted only if no axis varies more [rad/s]");
    v("online_window", online_window, "online: tracked ticks per bias estimate");
    v("online_max_rate_rad_s", online_max_rate_rad_s,
      "online: a re-estimate further than this is refused [rad/s]");
    v("online_gain", online_gain, "online: weight of a new estimate");
    v("gyro_noise_density", gyro_noise_density,
      "full: gyroscope white noise [rad/s/sqrt(Hz)] (Kalibr's gyroscope_noise_density)");
    v("accel_noise_density", accel_noise_density,
      "full: accelerometer white noise [m/s^2/sqrt(Hz)] (Kalibr's accelerometer_noise_density)");
    v("max_bridge_s", max_bridge_s,
      "full: longest stretch without events carried on the IMU alone (standstills excepted) [s]");
    v("time_offset_s", time_offset_s,
      "IMU clock minus camera clock [s] (Kalibr's timeshift_cam_imu: t_imu = t_cam + offset)");
  }
  Status Validate() const;
};

}  // namespace aavio::imu

namespace aavio {
template <>
struct EnumNames<imu::ImuMode> {
  static constexpr std::array kNames = {std::pair{imu::ImuMode::kOff, "off"},
                                        std::pair{imu::ImuMode::kGyro, "gyro"},
                                        std::pair{imu::ImuMode::kFull, "full"}};
};
template <>
struct EnumNames<imu::GyroBiasMode> {
  static constexpr std::array kNames = {std::pair{imu::GyroBiasMode::kFixed, "fixed"},
                                        std::pair{imu::GyroBiasMode::kStaticInit, "static_init"},
                                        std::pair{imu::GyroBiasMode::kOnline, "online"}};
};
}  // namespace aavio
