#include "aavio/imu/imu_config.hpp"

#include <cmath>

namespace aavio::imu {

Status ImuConfig::Validate() const {
  FieldChecker check;
  for (double b : gyro_bias_rad_s) {
    check.Require(std::abs(b) < 1.0, "gyro_bias_rad_s",
                  "has a component of " + FieldChecker::Num(b) +
                      " rad/s; a gyroscope bias is a few mrad/s (is it in deg/s?)");
  }
  check.InRange("static_init_s", static_init_s, 0.01, 600.0)
      .InRange("static_max_std_rad_s", static_max_std_rad_s, 1e-6, 1.0)
      .InRange("online_window", online_window, 2, 100000)
      .InRange("online_max_rate_rad_s", online_max_rate_rad_s, 1e-6, 1.0)
      .InRange("online_gain", online_gain, 1e-4, 1.0)
      .InRange("gyro_noise_density", gyro_noise_density, 1e-7, 1.0)
      .InRange("accel_noise_density", accel_noise_density, 1e-6, 10.0)
      .InRange("max_bridge_s", max_bridge_s, 0.0, 600.0);
  check.Require(std::abs(time_offset_s) <= 1.0, "time_offset_s",
                "= " + FieldChecker::Num(time_offset_s) +
                    " s; an IMU-camera time offset is a few milliseconds, given in seconds (is it "
                    "in ms?)");
  return check.status();
}

}  // namespace aavio::imu
