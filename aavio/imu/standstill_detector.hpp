#pragma once
/// A standstill from the IMU and the tracked poses, for a tracker without a velocity estimate
/// (imu.mode gyro): the zero-velocity update of inertial navigation. A standstill begins when the
/// registered poses of the last 0.2 s moved slower than kMaxSpeed and the readings are those of a
/// sensor at rest (standstill.hpp). While it lasts the pose holds and is not registered, so the
/// tracked speed stays what it was; the accelerometer, less the reading the standstill began with,
/// integrates a velocity instead. It ends when the readings stop reading rest, when their mean
/// moves kMaxReadingDrift from that reading (an acceleration in any direction, however smooth: a
/// car pulling away) or when the velocity reaches kMaxSpeed (a gentler one).
///
/// A camera pulling away steadily looks at rest again a moment later (steady readings, not far
/// gone): for kMemoryS after a standstill of kMinRememberedS or more, the reading it began with
/// (turned by the gyroscope) and the velocity since are kept, and a new one must agree with both —
/// a camera that moved and stopped again has come back to no velocity. Longer, the gyroscope's
/// bias has turned the reading too far (0.01 rad/s over 1 s: 0.1 m/s², 5 cm/s integrated) and it
/// is forgotten; a shorter standstill may have been the last centimetres of a braking, read as
/// rest, and the reading it began with is no reference.
///
/// What no reading can tell: a camera whose track moved slower than kMaxSpeed over 0.2 s while it
/// accelerated steadily (under 1 m/s², from rest or from a standstill shorter than
/// kMinRememberedS) reads a steady specific force, and is held as standing until that changes by
/// kMaxReadingDrift; registration then resumes from the held pose. A gravity direction known from
/// the tracking (the accelerometer's check measures one) would tell it, and is not consulted.

#include <Eigen/Core>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

class StandstillDetector {
 public:
  static constexpr double kMaxSpeed = 0.1;         ///< m/s; a still camera's track: a few mm/s
  static constexpr double kMaxReadingDrift = 0.2;  ///< m/s²
  static constexpr double kMemoryS = 1.0, kMinRememberedS = 0.5;

  /// IMU samples in time order (stamps not after the last are skipped).
  void AddSamples(std::span<const ImuSample> samples);
  /// A registered camera position (not a held or predicted one).
  void AddRegistered(TimeNs t_ns, const Eigen::Vector3d& p_world_cam);
  /// Tracking starts again: the speed is unknown until 0.2 s of registered positions.
  void Restart();

  /// Whether the camera stands still over the tick (t_prev_ns, t_ns], whose gyroscope rotation
  /// (IMU frame, bias removed) is `delta_R_imu` when known.
  bool Update(TimeNs t_prev_ns, TimeNs t_ns, const std::optional<Eigen::Matrix3d>& delta_R_imu,
              const Eigen::Vector3d& gyro_bias);

 private:
  bool SlowEnough() const;

  std::vector<ImuSample> recent_;                               // the last 0.2 s and more
  std::vector<std::pair<TimeNs, Eigen::Vector3d>> registered_;  // ~0.2 s of them
  bool standing_ = false;
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();  // since the standstill began, IMU frame
  // The specific force the last standstill began with (IMU frame, turned by the gyroscope since
  // it ended) and when it last stood.
  std::optional<Eigen::Vector3d> reading_;
  TimeNs reading_t_ns_ = 0;
  TimeNs began_t_ns_ = 0;
};

}  // namespace aavio::imu
