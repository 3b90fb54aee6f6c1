#include "aavio/tracking/tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "aavio/geometry/rotation.hpp"
#include "aavio/imu/gyro_preintegration.hpp"

namespace aavio::tracking {

namespace {
// Lost when the map points' mean cost is above this share of the image's: the registration found
// no pose where the map fits the time surface better than anywhere (a blackout, a flash, pure
// noise). Tracked ticks of the rpg and DSEC twins stay at or below 0.89 (median 0.4-0.75), ticks
// of events at random pixels at 0.93-1.
constexpr double kMaxAlignment = 0.95;
// Full mode: how long events that do not register are bridged on the IMU (braking to a stop, a
// blur) [s]. Longer is worse: after a dark stretch, events that keep failing mean the map no longer
// fits, and it is better re-initialised at once (DSEC 04a dark twin, seed 4: 0.21 m ATE, against
// 0.28 m bridging them for max_bridge_s).
constexpr double kMaxDivergenceBridgeS = 0.5;

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}
}  // namespace

const char* TrackingStatusName(TrackingStatus status) {
  switch (status) {
    case TrackingStatus::kOk:
      return "ok";
    case TrackingStatus::kLost:
      return "lost";
    case TrackingStatus::kNoMap:
      return "no_map";
    case TrackingStatus::kImuOnly:
      return "imu";
  }
  return "?";
}

const char* LostReasonName(LostReason reason) {
  switch (reason) {
    case LostReason::kNone:
      return "none";
    case LostReason::kFewValid:
      return "few_valid_residuals";
    case LostReason::kNotAligned:
      return "not_aligned";
    case LostReason::kCostGrew:
      return "cost_grew";
    case LostReason::kRotationJump:
      return "rotation_jump";
    case LostReason::kTranslationJump:
      return "translation_jump";
    case LostReason::kNoEvents:
      return "no_events";
    case LostReason::kImuDisagrees:
      return "imu_disagrees";
  }
  return "?";
}

geometry::RigidTransform PredictPose(
    const geometry::RigidTransform& T_world_prev,
    const std::optional<geometry::RigidTransform>& T_world_prevprev,
    const std::optional<Eigen::Matrix3d>& delta_R_cam,
    const std::optional<Eigen::Vector3d>& velocity_per_tick) {
  geometry::RigidTransform pred = T_world_prev;
  if (velocity_per_tick) pred.t = T_world_prev.t + *velocity_per_tick;
  if (T_world_prevprev) {
    if (!velocity_per_tick) pred.t = T_world_prev.t + (T_world_prev.t - T_world_prevprev->t);
    if (!delta_R_cam) {
      pred.R = geometry::Orthonormalize(T_world_prev.R *
                                        (T_world_prevprev->R.transpose() * T_world_prev.R));
    }
  }
  if (delta_R_cam) pred.R = geometry::Orthonormalize(T_world_prev.R * *delta_R_cam);
  return pred;
}

Tracker::Tracker(const Camera& camera, const TrackingConfig& config,
                 const imu::ImuConfig& imu_config, const geometry::RigidTransform& T_imu_cam,
                 std::uint64_t seed)
    : camera_(camera),
      config_(config),
      imu_config_(imu_config),
      R_imu_cam_(T_imu_cam.R),
      seed_(seed) {
  if (imu_config.mode == imu::ImuMode::kFull) back_end_.emplace(imu_config, T_imu_cam);
}

Eigen::Vector3d Tracker::gyro_bias() const {
  if (back_end_ && back_end_->ready()) return back_end_->state().gyro_bias;
  return bias_ ? bias_->bias() : Eigen::Vector3d::Zero();
}

std::optional<imu::ImuState> Tracker::imu_state() const {
  if (back_end_ && back_end_->ready()) return back_end_->state();
  return std::nullopt;
}

bool Tracker::Starved(std::int64_t new_events) const {
  // Relative to what this sensor and scene gave lately (8 tracked ticks at least), so that no
  // rate is assumed; a tenth: the event rate of a moving camera varies by less within a tick.
  constexpr double kStarvedFraction = 0.1;
  if (new_events < 0 || recent_events_.size() < 8) return false;
  std::vector<std::int64_t> sorted = recent_events_;
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  return static_cast<double>(new_events) < kStarvedFraction * static_cast<double>(*mid);
}

void Tracker::Reset(TimeNs t_ns, const geometry::RigidTransform& T_world_cam, bool keep_velocity) {
  if (!seed_origin_ns_) seed_origin_ns_ = t_ns;
  t_prev_ = t_ns;
  T_prev_ = T_world_cam;
  T_prevprev_.reset();
  if (!keep_velocity) velocity_.setZero();
  prev_tracked_ = false;
  last_tracked_ns_ = t_ns;
  if (!bias_) bias_.emplace(imu_config_, t_ns);
  if (back_end_) {
    back_end_->Restart();
    back_end_->AddPose(t_ns, T_world_cam, /*tracked=*/false);
  }
}

TrackingResult Tracker::Track(const events::Observation& obs, const cv::Mat& valid_mask,
                              std::span<const imu::ImuSample> imu) {
  TrackingResult result;
  result.t_ns = obs.t_ns;
  auto start = Clock::now();
  if (!bias_) bias_.emplace(imu_config_, t_prev_);
  bias_->AddSamples(imu);
  if (back_end_) back_end_->AddSamples(imu);
  std::optional<Eigen::Matrix3d> delta_R_imu, delta_R_cam;
  if (!imu.empty()) {
    Expected<Eigen::Matrix3d> delta = imu::IntegrateGyro(imu, t_prev_, obs.t_ns, gyro_bias());
    if (delta) delta_R_imu = *delta;
  }
  if (imu_config_.mode != imu::ImuMode::kOff && delta_R_imu)
    delta_R_cam = imu::ImuToCameraRotation(*delta_R_imu, R_imu_cam_);
  // The velocity is a translation per tick: over a longer interval (ticks skipped by a live
  // input that fell behind) it is scaled to this one.
  const TimeNs dt_ns = obs.t_ns - t_prev_;
  if (velocity_dt_ns_ > 0 && dt_ns > 0 && dt_ns != velocity_dt_ns_) {
    velocity_ *= static_cast<double>(dt_ns) / static_cast<double>(velocity_dt_ns_);
  }
  velocity_dt_ns_ = dt_ns;
  // velocity_gain 0 is ESVO's zero-motion model: the rotation is held too (else, without the
  // gyroscope, it continues the last tick's).
  const bool zero_motion = config_.velocity_gain == 0.0;
  geometry::RigidTransform predicted =
      PredictPose(T_prev_, zero_motion ? std::nullopt : T_prevprev_, delta_R_cam, velocity_);
  // Full mode: the back-end's 6-DoF prediction; at rest (a standstill the IMU sees), the pose
  // holds.
  const bool at_rest = back_end_ && back_end_->ready() && back_end_->AtRest(t_prev_, obs.t_ns);
  if (back_end_ && back_end_->ready()) {
    if (at_rest) {
      predicted = T_prev_;
    } else if (Expected<geometry::RigidTransform> imu_pose = back_end_->Predict(obs.t_ns)) {
      predicted = *imu_pose;
    }
  }
  result.prediction_ms = MsSince(start);
  result.T_world_cur = predicted;
  result.T_world_predicted = predicted;
  result.status = TrackingStatus::kNoMap;
  const bool has_map =
      map_ && static_cast<int>(map_->points_world.size()) >= config_.min_map_points;
  // Full mode: a tick the events cannot register is carried on the IMU (the prediction), however
  // long a standstill lasts, else for max_bridge_s since the last tracked tick (or the end of a
  // standstill) when there are no events, and for kMaxDivergenceBridgeS when there are but they
  // do not register (beyond that the map, not the events, is off: lost, and re-initialised).
  const double unregistered_s = NsToSeconds(obs.t_ns - last_tracked_ns_);
  const bool imu_ready = back_end_ && back_end_->ready();
  const bool can_bridge = imu_ready && (at_rest || unregistered_s <= imu_config_.max_bridge_s);
  const bool can_bridge_divergence =
      imu_ready && (at_rest || unregistered_s <= kMaxDivergenceBridgeS);
  if (has_map && Starved(obs.new_events_left)) {
    // Nothing new to register on: the time surface only fades. Hold the prediction.
    result.status = can_bridge ? TrackingStatus::kImuOnly : TrackingStatus::kLost;
    result.lost_reason = can_bridge ? LostReason::kNone : LostReason::kNoEvents;
  } else if (has_map) {
    start = Clock::now();
    // The map in its reference frame; the increment acts on T_ref,cur.
    const geometry::RigidTransform T_ref_world = map_->T_world_ref.Inverse();
    std::vector<Eigen::Vector3d> points_ref;
    points_ref.reserve(map_->points_world.size());
    for (const Eigen::Vector3d& p : map_->points_world)
      points_ref.push_back(T_ref_world * p);
    const TimeNs since_origin_ns = obs.t_ns - seed_origin_ns_.value_or(0);
    const Registration registration(points_ref, camera_, config_,
                                    seed_ ^ static_cast<std::uint64_t>(since_origin_ns));
    const RegistrationImages images{obs.negative_ts_left, obs.grad_u, obs.grad_v, valid_mask};
    const geometry::RigidTransform T_ref_predicted = T_ref_world * predicted;
    std::optional<Eigen::Matrix3d> R_prior;
    if (delta_R_cam) R_prior = T_ref_predicted.R;  // the gyroscope's rotation
    result.registration = registration.Solve(images, T_ref_predicted, R_prior);
    result.registration_ms = MsSince(start);
    const geometry::RigidTransform estimate = map_->T_world_ref * result.registration.T_ref_cur;
    // Divergence: too few residuals inside the image, a map that fits no better here than
    // anywhere, a cost that grew, or a pose implausibly far from the prediction (with the
    // gyroscope: a rotation the IMU did not measure).
    const geometry::RigidTransform correction = predicted.Inverse() * estimate;
    const double rotation_deg = geometry::LogSO3(correction.R).norm() * 180.0 / M_PI;
    if (result.registration.valid_fraction < 0.3)
      result.lost_reason = LostReason::kFewValid;
    else if (result.registration.alignment > kMaxAlignment)
      result.lost_reason = LostReason::kNotAligned;
    else if (result.registration.final_cost > 1.5 * result.registration.initial_cost)
      result.lost_reason = LostReason::kCostGrew;
    else if (rotation_deg > config_.max_correction_deg)
      result.lost_reason = LostReason::kRotationJump;
    else if (correction.t.norm() > config_.max_correction_m)
      result.lost_reason = LostReason::kTranslationJump;
    const bool diverged = result.lost_reason != LostReason::kNone;
    if (!diverged) {
      result.status = TrackingStatus::kOk;
      result.T_world_cur = estimate;
    } else if (can_bridge_divergence) {  // the events do not register (braking, a blur)
      result.status = TrackingStatus::kImuOnly;
      result.lost_reason = LostReason::kNone;
    } else {
      result.status = TrackingStatus::kLost;
    }
  }
  // Online bias: the tracked rotation of this tick, in the IMU frame, against pre-integration.
  if (result.status == TrackingStatus::kOk && delta_R_imu) {
    const Eigen::Matrix3d tracked_cam = T_prev_.R.transpose() * result.T_world_cur.R;
    bias_->AddTrackedTick(imu, t_prev_, obs.t_ns, R_imu_cam_ * tracked_cam * R_imu_cam_.transpose(),
                          prev_tracked_);
  }
  prev_tracked_ = result.status == TrackingStatus::kOk;
  // Lost: hold the prediction and coast on the velocity; without a map: forget it.
  if (result.status == TrackingStatus::kOk && obs.new_events_left >= 0) {
    constexpr std::size_t kRecentTicks = 32;
    if (recent_events_.size() < kRecentTicks) {
      recent_events_.push_back(obs.new_events_left);
    } else {
      recent_events_[recent_next_] = obs.new_events_left;
    }
    recent_next_ = (recent_next_ + 1) % kRecentTicks;
  }
  if (back_end_) {  // the back-end's update counts as prediction (the IMU's share of a tick)
    const auto update = Clock::now();
    back_end_->AddPose(obs.t_ns, result.T_world_cur, result.status == TrackingStatus::kOk);
    result.prediction_ms += MsSince(update);
  }
  // The bridge's clock counts motion without registration: a standstill does not use it up.
  if (result.status == TrackingStatus::kOk ||
      (result.status == TrackingStatus::kImuOnly && at_rest))
    last_tracked_ns_ = obs.t_ns;
  if (result.status == TrackingStatus::kOk) {
    const double gain = config_.velocity_gain;
    velocity_ = gain * (result.T_world_cur.t - T_prev_.t) + (1.0 - gain) * velocity_;
  } else if (result.status == TrackingStatus::kImuOnly) {
    velocity_ = result.T_world_cur.t - T_prev_.t;  // the IMU's, should the back-end stop
  } else if (result.status == TrackingStatus::kLost) {
    velocity_ *= config_.lost_velocity_decay;
  } else {
    velocity_.setZero();
  }
  T_prevprev_ = result.status == TrackingStatus::kOk ? std::optional(T_prev_) : std::nullopt;
  T_prev_ = result.T_world_cur;
  t_prev_ = obs.t_ns;
  ++ticks_;
  return result;
}

}  // namespace aavio::tracking
