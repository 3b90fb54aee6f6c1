#pragma once
/// What the IMU tells tracking at each tick (docs/tracking.md): the gyroscope's rotation over the
/// tick (the paper's prior, with the bias estimated as imu.bias says), whether the camera stands
/// still, and with imu.mode full the back-end's 6-DoF prediction and for how long ticks the events
/// do not register may be carried on it. Fed the IMU samples and the tracked poses.

#include <optional>
#include <span>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/imu/gyro_bias_estimator.hpp"
#include "aavio/imu/imu_back_end.hpp"
#include "aavio/imu/imu_config.hpp"
#include "aavio/imu/imu_sample.hpp"
#include "aavio/imu/standstill_detector.hpp"

namespace aavio::tracking {

/// The IMU's prior for one tick.
struct TickPrior {
  /// The gyroscope's rotation over the tick in the IMU frame (bias removed), if it covers it.
  std::optional<Eigen::Matrix3d> delta_R_imu;
  /// ... in the camera frame, when imu.mode uses the gyroscope (the registration's prior).
  std::optional<Eigen::Matrix3d> delta_R_cam;
  /// imu.mode full, once the back-end has an estimate: the pose it predicts; at rest (any mode
  /// using the IMU): the previous pose.
  std::optional<geometry::RigidTransform> T_world_cur;
  /// A standstill over the tick: the readings of a sensor at rest (standstill.hpp) and a low speed
  /// (the back-end's estimate; with imu.mode gyro, standstill_detector.hpp).
  bool at_rest = false;
  /// imu.mode gyro at a standstill: the pose holds and the tick is not registered (a still
  /// camera's events are noise and fading edges, on which a registration only slides).
  bool hold = false;
  bool can_bridge = false;             ///< events missing: the tick may be carried on the IMU
  bool can_bridge_divergence = false;  ///< events that do not register: ... likewise
};

class ImuPrior {
 public:
  /// `T_imu_cam`: the rectified left camera → IMU (see gyro_preintegration.hpp).
  ImuPrior(const imu::ImuConfig& config, const geometry::RigidTransform& T_imu_cam);

  /// Starts again at a known pose (tracking restarts), keeping the gyroscope bias estimate.
  void Restart(TimeNs t_ns, const geometry::RigidTransform& T_world_cam);
  /// The prior of the tick (t_prev_ns, t_ns], whose samples `imu` covers it, from the pose at
  /// t_prev_ns; `unregistered_s`: data time since the last registered (or standing) tick.
  TickPrior ForTick(std::span<const imu::ImuSample> imu, TimeNs t_prev_ns, TimeNs t_ns,
                    const geometry::RigidTransform& T_world_prev, double unregistered_s);
  /// A registered tick's rotation (camera frame) against the gyroscope's: the online bias.
  /// `previous_registered`: the tick before was registered too.
  void AddRegisteredTick(std::span<const imu::ImuSample> imu, TimeNs t_prev_ns, TimeNs t_ns,
                         const TickPrior& prior, const Eigen::Matrix3d& delta_R_cam_tracked,
                         bool previous_registered);
  /// Every tick's pose, for the back-end (`registered`: from the events, else carried).
  void AddPose(TimeNs t_ns, const geometry::RigidTransform& T_world_cam, bool registered);

  /// The gyroscope bias in use (configured, static-init, online or the back-end's estimate).
  Eigen::Vector3d gyro_bias() const;
  /// The back-end's estimate (imu.mode full, once it has one).
  std::optional<imu::ImuState> state() const;

 private:
  imu::ImuConfig config_;
  Eigen::Matrix3d R_imu_cam_;
  std::optional<imu::GyroBiasEstimator> bias_;
  std::optional<imu::ImuBackEnd> back_end_;  ///< imu.mode full
  imu::StandstillDetector standstill_;       ///< imu.mode gyro
};

}  // namespace aavio::tracking
