#include "aavio/tracking/tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "aavio/geometry/rotation.hpp"

namespace aavio::tracking {

namespace {
// Lost when the map points' mean cost is above this share of the image's: the registration found
// no pose where the map fits the time surface better than anywhere (a blackout, a flash, pure
// noise). Tracked ticks of the rpg and DSEC twins stay at or below 0.89 (median 0.4-0.75), ticks
// of events at random pixels at 0.93-1.
constexpr double kMaxAlignment = 0.95;

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Why a registration diverged, if it did: too few residuals inside the image, a map that fits no
// better here than anywhere, a cost that grew, or a pose implausibly far from the prediction
// (`correction`: prediction → estimate; with the gyroscope: a rotation the IMU did not measure).
LostReason Divergence(const RegistrationResult& registration,
                      const geometry::RigidTransform& correction, const TrackingConfig& config) {
  const double rotation_deg = geometry::LogSO3(correction.R).norm() * 180.0 / M_PI;
  if (registration.valid_fraction < 0.3) return LostReason::kFewValid;
  if (registration.alignment > kMaxAlignment) return LostReason::kNotAligned;
  if (registration.final_cost > 1.5 * registration.initial_cost) return LostReason::kCostGrew;
  if (rotation_deg > config.max_correction_deg) return LostReason::kRotationJump;
  if (correction.t.norm() > config.max_correction_m) return LostReason::kTranslationJump;
  return LostReason::kNone;
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
                 std::uint64_t seed, const std::optional<StereoCheckRig>& stereo)
    : camera_(camera),
      config_(config),
      stereo_(config.stereo_check ? stereo : std::nullopt),
      imu_(imu_config, T_imu_cam),
      seed_(seed) {}

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
  imu_.Restart(t_ns, T_world_cam);
}

TrackingResult Tracker::Track(const events::Observation& obs, const cv::Mat& valid_mask,
                              std::span<const imu::ImuSample> imu) {
  TrackingResult result;
  result.t_ns = obs.t_ns;
  const auto start = Clock::now();
  const TickPrior prior =
      imu_.ForTick(imu, t_prev_, obs.t_ns, T_prev_, NsToSeconds(obs.t_ns - last_tracked_ns_));
  const geometry::RigidTransform predicted = Predict(obs.t_ns, prior);
  result.prediction_ms = MsSince(start);
  result.T_world_cur = predicted;
  result.T_world_predicted = predicted;
  result.status = TrackingStatus::kNoMap;
  if (map_ && static_cast<int>(map_->points_world.size()) >= config_.min_map_points) {
    if (prior.hold) {
      // A standstill the IMU sees (imu_prior.hpp): the pose holds.
      result.status = TrackingStatus::kImuOnly;
    } else if (Starved(obs.new_events_left)) {
      // Nothing new to register on: the time surface only fades. Hold the prediction.
      result.status = prior.can_bridge ? TrackingStatus::kImuOnly : TrackingStatus::kLost;
      result.lost_reason = prior.can_bridge ? LostReason::kNone : LostReason::kNoEvents;
    } else {
      const geometry::RigidTransform estimate =
          Register(obs, valid_mask, predicted, prior.delta_R_cam.has_value(), &result);
      Classify(estimate, prior, &result);
    }
  }
  UpdateMotion(obs, imu, prior, &result);
  return result;
}

geometry::RigidTransform Tracker::Predict(TimeNs t_ns, const TickPrior& prior) {
  // The velocity is a translation per tick: over a longer interval (ticks skipped by a live
  // input that fell behind) it is scaled to this one.
  const TimeNs dt_ns = t_ns - t_prev_;
  if (velocity_dt_ns_ > 0 && dt_ns > 0 && dt_ns != velocity_dt_ns_) {
    velocity_ *= static_cast<double>(dt_ns) / static_cast<double>(velocity_dt_ns_);
  }
  velocity_dt_ns_ = dt_ns;
  // velocity_gain 0 is ESVO's zero-motion model: the rotation is held too (else, without the
  // gyroscope, it continues the last tick's).
  const bool zero_motion = config_.velocity_gain == 0.0;
  const geometry::RigidTransform predicted =
      PredictPose(T_prev_, zero_motion ? std::nullopt : T_prevprev_, prior.delta_R_cam, velocity_);
  // Full mode: the back-end's 6-DoF prediction instead.
  return prior.T_world_cur.value_or(predicted);
}

geometry::RigidTransform Tracker::Register(const events::Observation& obs,
                                           const cv::Mat& valid_mask,
                                           const geometry::RigidTransform& T_world_predicted,
                                           bool gyro_prior, TrackingResult* result) const {
  const auto start = Clock::now();
  // The map in its reference frame; the increment acts on T_ref,cur.
  const geometry::RigidTransform T_ref_world = map_->T_world_ref.Inverse();
  std::vector<Eigen::Vector3d> points_ref;
  points_ref.reserve(map_->points_world.size());
  for (const Eigen::Vector3d& p : map_->points_world)
    points_ref.push_back(T_ref_world * p);
  const TimeNs since_origin_ns = obs.t_ns - seed_origin_ns_.value_or(0);
  const geometry::RigidTransform T_ref_predicted = T_ref_world * T_world_predicted;
  // The stereo check, at the predicted pose, on the points the draw picks.
  std::function<bool(const Eigen::Vector3d&)> keep;
  std::optional<StereoCheck> check;
  if (stereo_ && !obs.ts_right.empty()) {
    check.emplace(obs.ts_left, obs.ts_right, valid_mask, camera_, *stereo_);
    const geometry::RigidTransform T_cur_ref = T_ref_predicted.Inverse();
    keep = [&check, T_cur_ref](const Eigen::Vector3d& p_ref) {
      return !check->SeesSomethingElse(T_cur_ref * p_ref);
    };
  }
  const Registration registration(points_ref, camera_, config_,
                                  seed_ ^ static_cast<std::uint64_t>(since_origin_ns), keep);
  result->stereo_left_out = registration.left_out();
  const RegistrationImages images{obs.negative_ts_left, obs.grad_u, obs.grad_v, valid_mask};
  std::optional<Eigen::Matrix3d> R_prior;
  if (gyro_prior) R_prior = T_ref_predicted.R;  // the gyroscope's rotation
  result->registration = registration.Solve(images, T_ref_predicted, R_prior);
  result->registered = true;
  result->registration_ms = MsSince(start);
  return map_->T_world_ref * result->registration.T_ref_cur;
}

void Tracker::Classify(const geometry::RigidTransform& T_world_estimate, const TickPrior& prior,
                       TrackingResult* result) const {
  result->lost_reason = Divergence(result->registration,
                                   result->T_world_predicted.Inverse() * T_world_estimate, config_);
  if (result->lost_reason == LostReason::kNone) {
    result->status = TrackingStatus::kOk;
    result->T_world_cur = T_world_estimate;
  } else if (prior.can_bridge_divergence) {  // the events do not register (braking, a blur)
    result->status = TrackingStatus::kImuOnly;
    result->lost_reason = LostReason::kNone;
  } else {
    result->status = TrackingStatus::kLost;
  }
}

void Tracker::UpdateMotion(const events::Observation& obs, std::span<const imu::ImuSample> imu,
                           const TickPrior& prior, TrackingResult* result) {
  const bool registered = result->status == TrackingStatus::kOk;
  // Online bias: the tracked rotation of this tick against pre-integration.
  if (registered) {
    imu_.AddRegisteredTick(imu, t_prev_, obs.t_ns, prior,
                           T_prev_.R.transpose() * result->T_world_cur.R, prev_tracked_);
  }
  prev_tracked_ = registered;
  if (registered && obs.new_events_left >= 0) {
    constexpr std::size_t kRecentTicks = 32;
    if (recent_events_.size() < kRecentTicks) {
      recent_events_.push_back(obs.new_events_left);
    } else {
      recent_events_[recent_next_] = obs.new_events_left;
    }
    recent_next_ = (recent_next_ + 1) % kRecentTicks;
  }
  const auto update = Clock::now();  // the back-end's update counts as the IMU's share
  imu_.AddPose(obs.t_ns, result->T_world_cur, registered);
  result->prediction_ms += MsSince(update);
  // The bridge's clock counts motion without registration: a standstill does not use it up.
  if (registered || (result->status == TrackingStatus::kImuOnly && prior.at_rest))
    last_tracked_ns_ = obs.t_ns;
  // Lost: hold the prediction and coast on the velocity; without a map: forget it.
  if (registered) {
    const double gain = config_.velocity_gain;
    velocity_ = gain * (result->T_world_cur.t - T_prev_.t) + (1.0 - gain) * velocity_;
  } else if (result->status == TrackingStatus::kImuOnly) {
    velocity_ = result->T_world_cur.t - T_prev_.t;  // the IMU's, should the back-end stop
  } else if (result->status == TrackingStatus::kLost) {
    velocity_ *= config_.lost_velocity_decay;
  } else {
    velocity_.setZero();
  }
  T_prevprev_ = registered ? std::optional(T_prev_) : std::nullopt;
  T_prev_ = result->T_world_cur;
  t_prev_ = obs.t_ns;
  ++ticks_;
}

}  // namespace aavio::tracking
