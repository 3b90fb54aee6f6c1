#pragma once
/// Configuration of the gyroscope prior (algorithm.md §5.6). The IMU–camera extrinsic is part
/// of the calibration (StereoRig::T_imu_left), not of this config.

#include <array>
#include <utility>

#include "aavio/common/config_fields.hpp"

namespace aavio::imu {

enum class GyroBiasMode {
  kFixed,       ///< gyro_bias_rad_s as configured [paper: "initialised empirically, not updated"]
  kStaticInit,  ///< mean gyro reading over an initial static interval
  kOnline,      ///< re-estimated from tracked vs pre-integrated rotations (as ESVO2 does)
};

struct ImuConfig {
  bool use_gyro_prior = true;  ///< initial rotation of registration from the gyroscope [paper]
  GyroBiasMode bias_mode = GyroBiasMode::kFixed;
  std::array<double, 3> gyro_bias_rad_s{0.0, 0.0, 0.0};  ///< in the IMU frame ([ICRA] zero)
  double static_init_s = 1.0;  ///< length of the static interval for static_init [s]
  /// static_init accepts the interval only if no axis' readings have a larger std [rad/s]
  double static_max_std_rad_s = 0.02;
  int online_window = 20;  ///< consecutive tracked ticks in the online estimate's window
  /// online: a re-estimate further than this from the current bias is a tracking failure [rad/s]
  double online_max_rate_rad_s = 0.05;
  double online_gain = 0.2;  ///< online: weight of a new window's estimate once warmed up

  template <typename V>
  void VisitFields(V&& v) {
    v("use_gyro_prior", use_gyro_prior,
      "the pre-integrated gyroscope rotation starts each registration (paper)");
    v("bias_mode", bias_mode, "gyroscope bias: fixed (gyro_bias_rad_s), static_init or online");
    v("gyro_bias_rad_s", gyro_bias_rad_s, "gyroscope bias in the IMU frame [rad/s]");
    v("static_init_s", static_init_s, "static_init: length of the initial still interval [s]");
    v("static_max_std_rad_s", static_max_std_rad_s,
      "static_init: accepted only if no axis varies more [rad/s]");
    v("online_window", online_window, "online: tracked ticks per bias estimate");
    v("online_max_rate_rad_s", online_max_rate_rad_s,
      "online: a re-estimate further than this is refused [rad/s]");
    v("online_gain", online_gain, "online: weight of a new estimate");
  }
  Status Validate() const;
};

}  // namespace aavio::imu

namespace aavio {
template <>
struct EnumNames<imu::GyroBiasMode> {
  static constexpr std::array kNames = {std::pair{imu::GyroBiasMode::kFixed, "fixed"},
                                        std::pair{imu::GyroBiasMode::kStaticInit, "static_init"},
                                        std::pair{imu::GyroBiasMode::kOnline, "online"}};
};
}  // namespace aavio
