#pragma once
/// Tracking at every tick (docs/tracking.md): predict the pose — rotation from the gyroscope
/// pre-integrated over the tick (or constant angular velocity without IMU), translation by
/// constant velocity; with imu.mode full, the whole pose from the IMU back-end once it has an
/// estimate — then register the local map on the negative time surface from it. A tick without
/// events to register on is carried on the IMU alone in full mode (kImuOnly), else lost.
/// Divergence (too few valid residuals, a cost that grew, a rotation that disagrees with the
/// gyroscope) holds the prediction and reports kLost, so that mapping can re-initialise at the
/// last good pose.

#include <optional>
#include <span>
#include <vector>

#include "aavio/events/observation.hpp"
#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/imu/imu_config.hpp"
#include "aavio/imu/imu_sample.hpp"
#include "aavio/tracking/imu_prior.hpp"
#include "aavio/tracking/registration.hpp"
#include "aavio/tracking/stereo_check.hpp"

namespace aavio::tracking {

enum class TrackingStatus {
  kOk,
  kNoMap,
  kLost,
  kImuOnly,  ///< no events to register on: the pose carried by the IMU back-end (imu.mode full)
};

/// Why a tick was declared lost (the first test that failed, in this order).
enum class LostReason {
  kNone,
  kFewValid,         ///< under 30 % of the residuals inside the image and mask
  kNotAligned,       ///< the map fits the time surface no better than anywhere (noise, blackout)
  kCostGrew,         ///< the registration ended 50 % above its starting cost
  kRotationJump,     ///< corrected the prediction by more than max_correction_deg
  kTranslationJump,  ///< ... or by more than max_correction_m
  kNoEvents,      ///< under 10 % of the events of recent tracked ticks (darkness, a covered lens, a
                  ///< standstill): not registered; the pose holds, turned by the gyroscope
  kImuDisagrees,  ///< (set by the odometry) the tracked motion of the last 0.5 s contradicts the
                  ///< accelerometer (imu::InertialCheck): the track diverged; mapping restarts
};
const char* LostReasonName(LostReason reason);
/// "ok", "lost", "no_map" or "imu" (summary.json, timings.csv, the Python module).
const char* TrackingStatusName(TrackingStatus status);

/// What tracking registers against: map points in the world, and its reference pose.
struct TrackingMap {
  std::vector<Eigen::Vector3d> points_world;
  geometry::RigidTransform T_world_ref;
};

struct TrackingResult {
  TimeNs t_ns = 0;
  geometry::RigidTransform T_world_cur;
  geometry::RigidTransform T_world_predicted;  ///< the registration's starting point
  TrackingStatus status = TrackingStatus::kNoMap;
  LostReason lost_reason = LostReason::kNone;
  bool registered = false;  ///< the registration ran (a map, and events to register on)
  int stereo_left_out = 0;  ///< map points the stereo check left out of the registration
  RegistrationResult registration;
  double prediction_ms = 0.0, registration_ms = 0.0;
};

/// The predicted pose: rotation R_prev·ΔR_cam from the gyroscope if given, else constant angular
/// velocity; translation t_prev + v with v the given velocity per tick, or else t_prev −
/// t_prevprev.
geometry::RigidTransform PredictPose(
    const geometry::RigidTransform& T_world_prev,
    const std::optional<geometry::RigidTransform>& T_world_prevprev,
    const std::optional<Eigen::Matrix3d>& delta_R_cam,
    const std::optional<Eigen::Vector3d>& velocity_per_tick = std::nullopt);

class Tracker {
 public:
  /// `T_imu_cam`: the rectified left camera → IMU (see gyro_preintegration.hpp).
  /// `stereo`: the rig for config.stereo_check (without it the check is off).
  Tracker(const Camera& camera, const TrackingConfig& config, const imu::ImuConfig& imu_config,
          const geometry::RigidTransform& T_imu_cam, std::uint64_t seed,
          const std::optional<StereoCheckRig>& stereo = std::nullopt);

  /// Starts (or restarts, keeping the gyroscope bias estimate) at a known pose.
  void Reset(TimeNs t_ns, const geometry::RigidTransform& T_world_cam, bool keep_velocity = false);
  void SetMap(std::shared_ptr<const TrackingMap> map) { map_ = std::move(map); }
  const TrackingMap* map() const { return map_.get(); }
  /// The gyroscope bias in use (configured, static-init, online or the back-end's estimate);
  /// valid after Reset.
  Eigen::Vector3d gyro_bias() const { return imu_.gyro_bias(); }
  /// The back-end's estimate (imu.mode full, once it has one).
  std::optional<imu::ImuState> imu_state() const { return imu_.state(); }

  /// One tick: `imu` must cover [previous tick, this tick] when the gyroscope prior is on.
  /// Predict, register the map (if it has enough points and there are events), classify the
  /// result, update the motion model.
  TrackingResult Track(const events::Observation& obs, const cv::Mat& valid_mask,
                       std::span<const imu::ImuSample> imu);

 private:
  // The pose at t_ns before registration: the IMU's prior and the motion model.
  geometry::RigidTransform Predict(TimeNs t_ns, const TickPrior& prior);
  // Registration of the map from the prediction (`gyro_prior`: its rotation is the
  // gyroscope's); fills result->registration and returns the estimate.
  geometry::RigidTransform Register(const events::Observation& obs, const cv::Mat& valid_mask,
                                    const geometry::RigidTransform& T_world_predicted,
                                    bool gyro_prior, TrackingResult* result) const;
  // Tracked, carried on the IMU (the events do not register) or lost (the first test failed).
  void Classify(const geometry::RigidTransform& T_world_estimate, const TickPrior& prior,
                TrackingResult* result) const;
  // The IMU prior, the velocity and the previous poses learn the tick's outcome.
  void UpdateMotion(const events::Observation& obs, std::span<const imu::ImuSample> imu,
                    const TickPrior& prior, TrackingResult* result);

  Camera camera_;
  TrackingConfig config_;
  std::optional<StereoCheckRig> stereo_;  // set when config_.stereo_check
  ImuPrior imu_;
  TimeNs last_tracked_ns_ = 0;  ///< the last registered (or standing) tick: bridging
  std::uint64_t seed_;
  std::optional<TimeNs> seed_origin_ns_;  // the first Reset's time: seeds mix in time since it
  std::shared_ptr<const TrackingMap> map_;
  TimeNs t_prev_ = 0;
  geometry::RigidTransform T_prev_;
  std::optional<geometry::RigidTransform> T_prevprev_;
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();  // smoothed translation per tick
  TimeNs velocity_dt_ns_ = 0;  // the tick interval velocity_ is a translation over (0: unknown)
  bool prev_tracked_ = false;  // the previous pose came from registration
  std::int64_t ticks_ = 0;
  std::vector<std::int64_t> recent_events_;  // new left events of the last tracked ticks (ring)
  std::size_t recent_next_ = 0;

  /// The tick's new events are too few to register on (LostReason::kNoEvents).
  bool Starved(std::int64_t new_events) const;
};

}  // namespace aavio::tracking
