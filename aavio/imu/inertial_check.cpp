#include "aavio/imu/inertial_check.hpp"

#include <algorithm>
#include <cmath>

#include "aavio/imu/imu_preintegration.hpp"

namespace aavio::imu {

InertialCheck::InertialCheck(const geometry::RigidTransform& T_imu_cam)
    : T_cam_imu_(T_imu_cam.Inverse()) {}

void InertialCheck::AddSamples(std::span<const ImuSample> samples) {
  for (const ImuSample& s : samples) {
    if (!samples_.empty() && s.t_ns <= samples_.back().t_ns) continue;
    samples_.push_back(s);
  }
  // Without anchors, the next one is a tracked pose from now on: older samples are not needed.
  if (anchors_.empty() && !samples_.empty()) Prune(samples_.back().t_ns - kAnchorSpacingNs);
}

void InertialCheck::Prune(TimeNs t_ns) {
  // Keeps the last sample at or before t_ns (an integration from t_ns interpolates from it).
  auto first_kept = samples_.begin();
  while (first_kept + 1 < samples_.end() && (first_kept + 1)->t_ns <= t_ns)
    ++first_kept;
  samples_.erase(samples_.begin(), first_kept);
}

void InertialCheck::Restart() {
  anchors_.clear();
  agreed_.clear();
  previous_error_.reset();
}

std::optional<Eigen::Vector3d> InertialCheck::GravityReference() const {
  if (agreed_.size() < kMinGravityMeasurements) return std::nullopt;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& g : agreed_)
    sum += g;
  return sum / static_cast<double>(agreed_.size());
}

std::optional<GravityMeasurement> InertialCheck::AddTrackedPose(
    TimeNs t_ns, const geometry::RigidTransform& T_world_cam, const Eigen::Vector3d& gyro_bias) {
  if (!anchors_.empty() && t_ns < anchors_.back().t_ns + kAnchorSpacingNs) return std::nullopt;
  const geometry::RigidTransform T_world_imu = T_world_cam * T_cam_imu_;
  anchors_.push_back({t_ns, T_world_imu.R, T_world_imu.t});
  if (anchors_.size() > 3) anchors_.pop_front();
  Prune(anchors_.front().t_ns);
  if (anchors_.size() < 3) return std::nullopt;

  const Anchor &a0 = anchors_[0], &a1 = anchors_[1], &a2 = anchors_[2];
  const std::span<const ImuSample> samples(samples_);
  const Eigen::Vector3d no_bias = Eigen::Vector3d::Zero();
  const auto span01 = Preintegrate(samples, a0.t_ns, a1.t_ns, gyro_bias, no_bias, ImuNoise{});
  const auto span12 = Preintegrate(samples, a1.t_ns, a2.t_ns, gyro_bias, no_bias, ImuNoise{});
  if (!span01.ok() || !span12.ok()) {
    // A gap in the IMU (or none yet): no verdict across it.
    anchors_.erase(anchors_.begin(), anchors_.end() - 1);
    agreed_.clear();
    previous_error_.reset();
    return std::nullopt;
  }
  const double d0 = span01->dt_s, d1 = span12->dt_s;
  // The mean velocities over each span, less what the accelerometer explains.
  const Eigen::Vector3d v01 =
      (a1.p_world_imu - a0.p_world_imu - a0.R_world_imu * span01->delta_p) / d0;
  const Eigen::Vector3d v12 =
      (a2.p_world_imu - a1.p_world_imu - a1.R_world_imu * span12->delta_p) / d1;
  GravityMeasurement m;
  m.t_ns = a1.t_ns;
  m.gravity_world = (v12 - v01 - a0.R_world_imu * span01->delta_v) / (0.5 * (d0 + d1));
  // What tracking that errs by kTrackingError of the distance travelled gives: an error of
  // ε = e·|v|·Δ in the middle anchor's position moves g by up to 4ε / Δ² (|v| the faster span's
  // mean speed).
  const double speed = std::max((a1.p_world_imu - a0.p_world_imu).norm() / d0,
                                (a2.p_world_imu - a1.p_world_imu).norm() / d1);
  const double span = 0.5 * (d0 + d1);
  m.tolerance_m_s2 = kMaxDisagreementMS2 + 4.0 * kTrackingError * speed / span;
  // Against gravity's direction once it is known, else its magnitude.
  const std::optional<Eigen::Vector3d> reference = GravityReference();
  if (!reference) {
    m.agrees = std::abs(m.gravity_world.norm() - kGravityMS2) <= m.tolerance_m_s2;
    previous_error_.reset();
  } else {
    // The error summed with the previous measurement's (the change of velocity over two spans):
    // a pose off at one anchor only (+1, -2, +1 over three measurements) leaves at most half of
    // what the middle measurement sees alone; a change of velocity or a jump shows in full.
    const Eigen::Vector3d error = m.gravity_world - *reference;
    const bool alone = error.norm() <= m.tolerance_m_s2;
    m.agrees = previous_error_ ? (error + *previous_error_).norm() <= m.tolerance_m_s2 : alone;
    previous_error_ = error;
    // Only a measurement that agrees on its own makes gravity's direction.
    if (!alone) return m;
  }
  if (m.agrees) {
    agreed_.push_back(m.gravity_world);
    if (agreed_.size() > kGravityMeasurements) agreed_.pop_front();
  }
  return m;
}

}  // namespace aavio::imu
