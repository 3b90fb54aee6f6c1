#include "aavio/imu/gyro_preintegration.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "aavio/common/format.hpp"

namespace aavio::imu {

Expected<Eigen::Matrix3d> IntegrateGyro(std::span<const ImuSample> samples, TimeNs t_begin,
                                        TimeNs t_end, const Eigen::Vector3d& gyro_bias) {
  if (t_end < t_begin) return InvalidArgument("pre-integration interval ends before it begins");
  if (samples.empty() || samples.front().t_ns > t_begin || samples.back().t_ns < t_end) {
    return OutOfRange(StrFormat("the IMU samples do not cover [%s, %s] s",
                                FormatSecondsNs(t_begin).c_str(), FormatSecondsNs(t_end).c_str()));
  }
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    const ImuSample& a = samples[k];
    const ImuSample& b = samples[k + 1];
    const TimeNs lo = std::max(a.t_ns, t_begin), hi = std::min(b.t_ns, t_end);
    if (hi <= lo) continue;
    // Mid-point rate over the clipped interval (the readings interpolated at its ends).
    const double span = static_cast<double>(b.t_ns - a.t_ns);
    auto at = [&](TimeNs t) {
      const double s = span > 0.0 ? static_cast<double>(t - a.t_ns) / span : 0.0;
      return Eigen::Vector3d((1.0 - s) * a.gyro_rad_s + s * b.gyro_rad_s);
    };
    const Eigen::Vector3d w = 0.5 * (at(lo) + at(hi)) - gyro_bias;
    const double dt = NsToSeconds(hi - lo);
    // The exact exponential of the mid-point rate (VINS uses its first-order form [1, ½ω dt]).
    const Eigen::Vector3d angle = w * dt;
    const double theta = angle.norm();
    q = q * (theta > 1e-15 ? Eigen::Quaterniond(Eigen::AngleAxisd(theta, angle / theta))
                           : Eigen::Quaterniond::Identity());
    q.normalize();
  }
  return q.toRotationMatrix();
}

Eigen::Matrix3d ImuToCameraRotation(const Eigen::Matrix3d& delta_R_imu,
                                    const Eigen::Matrix3d& R_imu_cam) {
  return R_imu_cam.transpose() * delta_R_imu * R_imu_cam;
}

Expected<Eigen::Vector3d> MeanGyro(std::span<const ImuSample> samples, TimeNs t_begin,
                                   TimeNs t_end) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (const ImuSample& s : samples) {
    if (s.t_ns < t_begin || s.t_ns > t_end) continue;
    sum += s.gyro_rad_s;
    ++n;
  }
  if (n == 0) return OutOfRange("no IMU samples in the static interval");
  return Eigen::Vector3d(sum / n);
}

}  // namespace aavio::imu
