#pragma once
/// Whether the tracked motion agrees with the accelerometer: the check that turns a silent
/// divergence of the visual tracking into a lost track.
///
/// Every 0.25 s of tracked poses is an anchor (the IMU's pose: rotation R, position p). Between
/// three consecutive anchors 0, 1, 2 the IMU pre-integrated over [0, 1] and [1, 2] (Δv, Δp, in
/// the IMU frame at each span's start) and the anchors' poses give gravity in the tracking's
/// world, with the two unknown velocities eliminated (Δ₀, Δ₁ the spans):
///   g = [ (p₂ − p₁ − R₁Δp₁₂)/Δ₁ − (p₁ − p₀ − R₀Δp₀₁)/Δ₀ − R₀Δv₀₁ ] / ((Δ₀ + Δ₁)/2).
/// Tracking that follows the camera gives gravity every time; a track that is pulled away (a
/// moving object taken for the scene, a repetitive texture, a faint scene where the camera turns
/// back) invents acceleration, and it shows in g at once. A constant error of velocity does not
/// show. The first verdict comes 0.5 s after tracking starts.
///
/// A measurement disagrees when it is further from gravity than its tolerance: 3 m/s² — 0.3 g of
/// acceleration invented or lost for 0.5 s, 9 cm of position — plus what a tracking error of 2 %
/// of the distance travelled gives at the anchors' speed v (4·0.02·v/Δ: 3.3 m/s² at a hand-held
/// 1 m/s, 6.5 m/s² at a car's 11 m/s). Until two measurements have agreed, only the magnitude
/// |g| − 9.81 is tested (no gravity direction is known yet: it sees an invented acceleration along
/// gravity fully and across it only as a²/2g); from then on the vector's error against the mean
/// of the last agreeing measurements (up to 2 s of them), which sees it in every direction, summed
/// with the previous measurement's error: that sum is the change of velocity over two spans, in
/// which a pose off at one anchor only (a tick the registration got wrong and the next got right)
/// counts half, a change of velocity or a jump in full and a steady error twice (a track
/// alternating ±d from anchor to anchor does not show in it). Gravity's direction in the tracked
/// world moves only as fast as the tracked rotation drifts, and a camera–IMU rotation error δ moves
/// it by at most 2δ·9.81 as the camera turns (0.34 m/s² for 1°). On the simulated twins (typical
/// sensor; rpg box, monitor, reader 10 s, DSEC 04a, 04c, 11a 4 s, seeds 1–5: 30 runs) one
/// measurement disagrees, on a slip of the track (13 cm within 0.25 s in rpg box seed 5).

#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

/// One measurement of gravity from three anchors (the middle anchor's time).
struct GravityMeasurement {
  TimeNs t_ns = 0;
  Eigen::Vector3d gravity_world = Eigen::Vector3d::Zero();  ///< [m/s²], in the tracking's world
  double tolerance_m_s2 = 0.0;  ///< how far from gravity it may be (grows with the speed)
  bool agrees = true;
};

class InertialCheck {
 public:
  /// `T_imu_cam`: camera → IMU (StereoRig::T_imu_rect_left).
  explicit InertialCheck(const geometry::RigidTransform& T_imu_cam);

  /// IMU samples in camera time, in time order (stamps not after the last are skipped).
  void AddSamples(std::span<const ImuSample> samples);
  /// A tracked pose of the camera (a tick registered on events), with the gyroscope bias in use.
  /// Returns a measurement when the pose completes an anchor that has two before it.
  std::optional<GravityMeasurement> AddTrackedPose(TimeNs t_ns,
                                                   const geometry::RigidTransform& T_world_cam,
                                                   const Eigen::Vector3d& gyro_bias);
  /// The poses are no longer one tracked stretch (not tracked, re-initialised): the anchors
  /// and the gravity measured start again from the next tracked pose.
  void Restart();

  /// How many of the last agreeing measurements make gravity's direction (2 s of them), and how
  /// many it takes before the direction is tested.
  static constexpr std::size_t kGravityMeasurements = 8, kMinGravityMeasurements = 2;
  /// Anchor spacing and the threshold of disagreement.
  static constexpr TimeNs kAnchorSpacingNs = 250'000'000;
  static constexpr double kMaxDisagreementMS2 = 3.0;
  /// The tracking error, as a fraction of the distance travelled, the tolerance allows for.
  static constexpr double kTrackingError = 0.02;

 private:
  struct Anchor {
    TimeNs t_ns;
    Eigen::Matrix3d R_world_imu;
    Eigen::Vector3d p_world_imu;
  };

  void Prune(TimeNs t_ns);

  /// The mean of the agreeing measurements kept; nullopt under kMinGravityMeasurements of them.
  std::optional<Eigen::Vector3d> GravityReference() const;

  geometry::RigidTransform T_cam_imu_;
  std::vector<ImuSample> samples_;
  std::deque<Anchor> anchors_;                     // the last three
  std::deque<Eigen::Vector3d> agreed_;             // gravity by the last agreeing measurements
  std::optional<Eigen::Vector3d> previous_error_;  // the last measurement's, against gravity
};

}  // namespace aavio::imu
