#include "aavio/imu/standstill.hpp"

#include <algorithm>
#include <cmath>

namespace aavio::imu {

std::optional<Eigen::Vector3d> RestReading(std::span<const ImuSample> samples, TimeNs t_begin_ns,
                                           TimeNs t_end_ns, const Eigen::Vector3d& gyro_bias,
                                           const Eigen::Vector3d& accel_bias) {
  t_begin_ns = std::min(t_begin_ns, t_end_ns - SecondsToNs(kRestSpanS));
  const auto first =
      std::lower_bound(samples.begin(), samples.end(), t_begin_ns,
                       [](const ImuSample& s, TimeNs t_ns) { return s.t_ns < t_ns; });
  const auto last = std::upper_bound(first, samples.end(), t_end_ns,
                                     [](TimeNs t_ns, const ImuSample& s) { return t_ns < s.t_ns; });
  const std::span<const ImuSample> span(first, last);
  if (span.size() < 2) return std::nullopt;
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero(), accel = Eigen::Vector3d::Zero();
  for (const ImuSample& s : span) {
    gyro += s.gyro_rad_s;
    accel += s.accel_m_s2;
  }
  const double n = static_cast<double>(span.size());
  const Eigen::Vector3d mean = accel / n;
  if ((gyro / n - gyro_bias).norm() >= kRestGyroRadS ||
      std::abs((mean - accel_bias).norm() - kGravityMS2) >= kRestAccelMeanMs2) {
    return std::nullopt;
  }
  // The change of acceleration across the span (a least-squares line through the readings: a
  // start, a sway), and the velocity the readings' variations about their mean give, sample to
  // sample (a shake).
  double t_mean_s = 0.0;
  for (const ImuSample& s : span)
    t_mean_s += NsToSeconds(s.t_ns - span.front().t_ns);
  t_mean_s /= n;
  Eigen::Vector3d slope_sum = Eigen::Vector3d::Zero();
  double t_var = 0.0;
  for (const ImuSample& s : span) {
    const double dt_s = NsToSeconds(s.t_ns - span.front().t_ns) - t_mean_s;
    slope_sum += dt_s * (s.accel_m_s2 - mean);
    t_var += dt_s * dt_s;
  }
  const double length_s = NsToSeconds(span.back().t_ns - span.front().t_ns);
  if (t_var <= 0.0 || (slope_sum / t_var).norm() * length_s >= kRestAccelChange)
    return std::nullopt;
  Eigen::Vector3d dv = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i < span.size(); ++i) {
    dv += (span[i].accel_m_s2 - mean) * NsToSeconds(span[i].t_ns - span[i - 1].t_ns);
    if (dv.norm() >= kRestSpeedChange) return std::nullopt;
  }
  return mean - accel_bias;
}

}  // namespace aavio::imu
