#include "aavio/imu/motion_evidence.hpp"

#include <cmath>

namespace aavio::imu {

namespace {
constexpr TimeNs kWindowNs = 100'000'000;    // 0.1 s
constexpr double kTurningRadS = 3.0 * M_PI / 180.0;
constexpr double kAcceleratingMS2 = 1.0;
}  // namespace

void MotionEvidence::Add(std::span<const ImuSample> samples) {
  for (const ImuSample& s : samples) {
    if (!recent_.empty() && s.t_ns <= recent_.back().t_ns) continue;
    recent_.push_back(s);
  }
  while (!recent_.empty() && recent_.front().t_ns < recent_.back().t_ns - kWindowNs)
    recent_.pop_front();
}

bool MotionEvidence::Moving() const {
  if (recent_.empty()) return false;
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero(), accel = Eigen::Vector3d::Zero();
  for (const ImuSample& s : recent_) {
    gyro += s.gyro_rad_s;
    accel += s.accel_m_s2;
  }
  const double n = static_cast<double>(recent_.size());
  return (gyro / n).norm() > kTurningRadS ||
         std::abs((accel / n).norm() - kGravityMS2) > kAcceleratingMS2;
}

}  // namespace aavio::imu
