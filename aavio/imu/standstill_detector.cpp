#include "aavio/imu/standstill_detector.hpp"

#include <algorithm>

#include "aavio/imu/standstill.hpp"

namespace aavio::imu {

void StandstillDetector::AddSamples(std::span<const ImuSample> samples) {
  for (const ImuSample& s : samples)
    if (recent_.empty() || s.t_ns > recent_.back().t_ns) recent_.push_back(s);
}

void StandstillDetector::AddRegistered(TimeNs t_ns, const Eigen::Vector3d& p_world_cam) {
  registered_.emplace_back(t_ns, p_world_cam);
  const TimeNs span_ns = SecondsToNs(kRestSpanS);
  while (registered_.size() > 2 && t_ns - registered_[1].first >= span_ns)
    registered_.erase(registered_.begin());
}

void StandstillDetector::Restart() {
  registered_.clear();
  standing_ = false;
  reading_.reset();
}

bool StandstillDetector::SlowEnough() const {
  if (registered_.size() < 2) return false;
  const auto& [t0_ns, p0] = registered_.front();
  const auto& [t1_ns, p1] = registered_.back();
  const double span_s = NsToSeconds(t1_ns - t0_ns);
  return span_s >= kRestSpanS && (p1 - p0).norm() / span_s < kMaxSpeed;
}

bool StandstillDetector::Update(TimeNs t_prev_ns, TimeNs t_ns,
                                const std::optional<Eigen::Matrix3d>& delta_R_imu,
                                const Eigen::Vector3d& gyro_bias) {
  const TimeNs keep_from = std::min(t_prev_ns, t_ns - SecondsToNs(kRestSpanS));
  recent_.erase(recent_.begin(),
                std::find_if(recent_.begin(), recent_.end(),
                             [&](const ImuSample& s) { return s.t_ns >= keep_from; }));
  // The velocity since the last standstill began: the readings less the one it began with (turned
  // with the camera after it ended), until that is forgotten.
  if (reading_) {
    if (!standing_ && delta_R_imu) {
      *reading_ = delta_R_imu->transpose() * *reading_;
      velocity_ = delta_R_imu->transpose() * velocity_;
    }
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int n = 0;
    for (const ImuSample& s : recent_) {
      if (s.t_ns <= t_prev_ns || s.t_ns > t_ns) continue;
      sum += s.accel_m_s2;
      ++n;
    }
    if (n > 0) velocity_ += (sum / n - *reading_) * NsToSeconds(t_ns - t_prev_ns);
    if (!standing_ && t_ns - reading_t_ns_ > SecondsToNs(kMemoryS)) reading_.reset();
  }
  std::optional<Eigen::Vector3d> reading;
  if (standing_ || SlowEnough())
    reading = RestReading(recent_, t_prev_ns, t_ns, gyro_bias, Eigen::Vector3d::Zero());
  if (reading && reading_ &&
      ((*reading - *reading_).norm() >= kMaxReadingDrift || velocity_.norm() >= kMaxSpeed)) {
    reading.reset();
  }
  if (!reading) {
    // Moving off: the reading it began with is remembered for a while if it stood long enough to
    // have been still (a standstill caught in a braking's last centimetres read the braking).
    if (standing_ && reading_t_ns_ - began_t_ns_ < SecondsToNs(kMinRememberedS)) reading_.reset();
    standing_ = false;
    return false;
  }
  if (!reading_) {  // a standstill of its own
    reading_ = reading;
    velocity_.setZero();
    began_t_ns_ = t_ns;
  }
  standing_ = true;
  reading_t_ns_ = t_ns;
  return true;
}

}  // namespace aavio::imu
