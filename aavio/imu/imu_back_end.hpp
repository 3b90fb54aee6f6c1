#pragma once
/// The IMU back-end (imu.mode full; docs/tracking.md, in the manner of ESVO2's): over a sliding
/// window of tracked poses, the velocity of each window frame, the gyroscope and accelerometer
/// biases and the direction of gravity that best explain the IMU pre-integrated between them —
/// the poses held fixed as measurements, as ESVO2 does. From that state it predicts the full 6-DoF
/// pose of the next tick (rotation from the gyroscope, translation from velocity, gravity and the
/// accelerometer), and carries the pose on the IMU alone where the events cannot.
///
/// The solver is a small dense Gauss–Newton in the style of the registration's (a window of 41
/// frames is 131 unknowns): no Ceres. Residuals between window frames i and j (IMU frames, world
/// of the tracking):
///   r_R = Log(ΔR(b_g)ᵀ R_iᵀ R_j)
///   r_v = R_iᵀ (v_j − v_i − g Δt) − Δv(b_g, b_a)
///   r_p = R_iᵀ (p_j − p_i − v_i Δt − ½ g Δt²) − Δp(b_g, b_a)
/// weighted by the pre-integration's covariance plus the tracking's own noise, with weak priors
/// on the biases at the long-term estimates. |g| is fixed; its direction is 2 unknowns. Each
/// window's biases and gravity move the long-term ones (a running mean, then over 20 s); the
/// velocities are then solved again with those, and they are what predictions use.
///
/// All of it runs in data time, synchronously, in the tracking thread: deterministic.

#include <Eigen/Core>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/imu/imu_config.hpp"
#include "aavio/imu/imu_preintegration.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

/// What the back-end has estimated (IMU frame quantities in the tracking's world).
struct ImuState {
  TimeNs t_ns = 0;
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();  ///< of the IMU [m/s]
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();       ///< [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();      ///< [m/s²]
  Eigen::Vector3d gravity_world = Eigen::Vector3d::Zero();   ///< [m/s²], |g| = 9.81
};

class ImuBackEnd {
 public:
  /// `T_imu_cam`: camera → IMU (StereoRig::T_imu_rect_left).
  ImuBackEnd(const ImuConfig& config, const geometry::RigidTransform& T_imu_cam);

  /// IMU samples as they arrive (time-ordered; repeats of samples already seen are skipped).
  /// The back-end keeps what its window and the current tick need.
  void AddSamples(std::span<const ImuSample> samples);

  /// A pose of the camera at `t_ns`: `tracked` = registered on events (a measurement for the
  /// window), else carried by prediction. Every 50 ms of tracked poses becomes a frame of the
  /// window (2 s), and the window is solved again.
  void AddPose(TimeNs t_ns, const geometry::RigidTransform& T_world_cam, bool tracked);

  /// Forgets the window and the velocity (a re-initialisation or a jump of the pose): estimation
  /// starts again from the next tracked poses; the biases and gravity are kept as priors.
  void Restart();

  /// The window has been solved and its estimate is plausible.
  bool ready() const { return ready_; }
  /// The estimate at the newest window frame.
  const ImuState& state() const { return state_; }

  /// The camera pose at `t_ns` from the last pose given to AddPose: the gyroscope's rotation,
  /// the translation from the velocity, gravity and the accelerometer. Needs ready() and samples
  /// covering [last pose, t_ns].
  Expected<geometry::RigidTransform> Predict(TimeNs t_ns) const;

  /// A standstill at t_end: the estimated speed is low (under 0.5 m/s) and the readings since
  /// t_begin, and over 0.2 s at least, are those of a sensor at rest (no rotation, gravity alone
  /// and steady). Poses carried through one keep a zero velocity.
  bool AtRest(TimeNs t_begin_ns, TimeNs t_end_ns) const;

 private:
  struct Frame {
    TimeNs t_ns;
    Eigen::Matrix3d R_world_imu;
    Eigen::Vector3d p_world_imu;
    Eigen::Vector3d v_world;
    Preintegrated from_previous;  ///< the IMU from the previous frame to this one
    Eigen::Matrix<double, 9, 9> information = Eigen::Matrix<double, 9, 9>::Zero();  ///< its weight
  };
  void Solve();
  bool InitialiseGravityAndVelocities();
  /// One Gauss–Newton step over velocities, biases and gravity (or the velocities only); the
  /// cost before it.
  double GaussNewtonStep(bool fix_biases_and_gravity);
  /// Pre-integrations whose biases are far from the long-term ones are integrated again.
  void ReintegrateFarFromBiases();
  /// The pre-integration residual between two consecutive frames (rotation, velocity, position)
  /// and its Jacobian over (v_i, v_j, b_g, b_a, δg), δg on gravity's 2-D tangent.
  struct InertialFactor {
    Eigen::Matrix<double, 9, 1> r;
    Eigen::Matrix<double, 9, 14> J;
  };
  InertialFactor Linearize(const Frame& fi, const Frame& fj,
                           const Eigen::Matrix<double, 3, 2>& dg_ddelta) const;

  ImuConfig config_;
  geometry::RigidTransform T_imu_cam_, T_cam_imu_;
  ImuNoise noise_;
  std::vector<ImuSample> samples_;  ///< time-ordered, trimmed to the window
  std::deque<Frame> frames_;
  bool ready_ = false;
  ImuState state_;
  /// Biases and gravity pooled over the windows solved so far (running, then exponential mean).
  struct LongTerm {
    Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero(), accel_bias = Eigen::Vector3d::Zero();
    Eigen::Vector3d gravity_world = Eigen::Vector3d::Zero();
    int solves = 0;
  };
  LongTerm long_term_;
  // The last pose given (IMU frame) and the velocity there.
  TimeNs last_t_ns_ = 0;
  bool have_last_ = false;
  Eigen::Matrix3d last_R_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d last_p_ = Eigen::Vector3d::Zero(), last_v_ = Eigen::Vector3d::Zero();
};

}  // namespace aavio::imu
