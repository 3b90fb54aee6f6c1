#include "aavio/pipeline/odometry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

#include "aavio/mapping/static_stereo.hpp"

namespace aavio::pipeline {
namespace {

// A tick waits this long past its time (plus the IMU time offset) for the IMU sample that ends its
// window; then it runs with what has arrived (no IMU stream, or a gap in it).
constexpr TimeNs kMaxImuGapNs = 50 * kNsPerMs;

tracking::Camera CameraOf(const geometry::StereoRig& rig) {
  return {rig.width(), rig.height(), rig.focal_px(), rig.cx_left(), rig.cy()};
}

// Tracking's stereo check accepts matches as static stereo does; its row search reaches from
// infinity to twice the nearest mapped depth's disparity (a mover may come nearer than the map).
tracking::StereoCheckRig StereoCheckRigOf(const geometry::StereoRig& rig,
                                          const OdometryConfig& config) {
  const mapping::RectifiedStereo stereo = mapping::RectifiedStereo::FromRig(rig);
  const mapping::DisparityRange range =
      mapping::StaticDisparityRange(stereo, config.mapping.inv_depth_range());
  return {stereo.fb(), stereo.cx_left - stereo.cx_right, 0, 2 * range.max,
          config.mapping.static_stereo.zncc_threshold};
}

// The mapping period: a whole number of ticks.
TimeNs CycleNs(const OdometryConfig& config) {
  const int ticks = std::max(
      1, static_cast<int>(std::lround(config.time_surface.rate_hz / config.mapping.rate_hz)));
  return SecondsToNs(1.0 / config.time_surface.rate_hz) * ticks;
}

}  // namespace

Odometry::Odometry(const geometry::StereoRig& rig, const OdometryConfig& config, TimeNs start_ns,
                   const geometry::RigidTransform& T_world_start, bool run_mapping)
    : config_(config),
      rectification_(geometry::BuildStereoRectification(rig)),
      stereo_(mapping::RectifiedStereo::FromRig(rig)),
      builder_(rectification_, rig.width(), rig.height(), RepresentationConfigOf(config), start_ns),
      tracker_(CameraOf(rig), config.tracking, config.imu,
               rig.T_imu_rect_left().value_or(geometry::RigidTransform()),
               static_cast<std::uint64_t>(config.pipeline.random_seed),
               StereoCheckRigOf(rig, config)),
      camera_(CameraOf(rig)),
      decay_(config.time_surface.decay_ms, config.time_surface.adaptive_decay),
      mapping_(stereo_, rectification_.left.valid_mask, config.mapping,
               MappingRunner::ModeOf(config.pipeline), CycleNs(config)),
      history_(config.mapping.temporal_stereo),
      imu_offset_ns_(SecondsToNs(config.imu.time_offset_s)),
      last_t_end_ns_(start_ns),
      inertial_check_(rig.T_imu_rect_left().value_or(geometry::RigidTransform())),
      tick_ns_(SecondsToNs(1.0 / config.time_surface.rate_hz)),
      next_tick_ns_(start_ns + tick_ns_),
      last_tick_ns_(start_ns),
      cycle_ns_(CycleNs(config)),
      next_cycle_ns_(start_ns + cycle_ns_),
      run_mapping_(run_mapping),
      last_event_ns_(start_ns),
      T_world_held_(T_world_start) {
  tracker_.Reset(start_ns, T_world_start);
}

Odometry::~Odometry() = default;  // a mapping cycle still running is waited for

Status Odometry::Process(std::span<const events::Event> left, std::span<const events::Event> right,
                         std::span<const imu::ImuSample> imu, TimeNs t_end_ns, TickPolicy policy) {
  if (!left.empty() || !right.empty()) {
    const TimeNs first = std::min(left.empty() ? right.front().t_ns : left.front().t_ns,
                                  right.empty() ? left.front().t_ns : right.front().t_ns);
    if (first - last_event_ns_ > kEventGapNs) AAVIO_RETURN_IF_ERROR(SkipEventGap(first));
    last_event_ns_ = std::max({last_event_ns_, left.empty() ? first : left.back().t_ns,
                               right.empty() ? first : right.back().t_ns});
  }
  const auto start = std::chrono::steady_clock::now();
  AAVIO_RETURN_IF_ERROR(builder_.AddEvents(events::Camera::kLeft, left));
  AAVIO_RETURN_IF_ERROR(builder_.AddEvents(events::Camera::kRight, right));
  last_insertion_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  imu_.insert(imu_.end(), imu.begin(), imu.end());
  imu_seen_ = imu_seen_ || !imu.empty();
  last_t_end_ns_ = std::max(last_t_end_ns_, t_end_ns);
  // In a gap no tick takes IMU samples: keep the last second's, enough for the tick grid to
  // resume on, so that memory does not grow with the gap.
  const TimeNs keep_from_ns = last_t_end_ns_ - kNsPerS;
  if (keep_from_ns > last_event_ns_ + kEventGapNs) {
    while (imu_.size() > 2 && imu_[1].t_ns < keep_from_ns)
      imu_.pop_front();
  }
  return RunTicks(policy, /*finishing=*/false);
}

Status Odometry::SkipEventGap(TimeNs resume_ns) {
  // The ticks before the gap still waiting for IMU samples run with what there is.
  AAVIO_RETURN_IF_ERROR(RunTicks(TickPolicy::kEvery, /*finishing=*/true));
  pending_gap_ = EventGap{last_event_ns_, resume_ns};
  // The ticks go on at the last grid time at or before the events' return (that tick says
  // there was a gap, even if the data ends there), a whole number of ticks on.
  if (next_tick_ns_ <= resume_ns)
    next_tick_ns_ += (resume_ns - next_tick_ns_) / tick_ns_ * tick_ns_;
  last_tick_ns_ = next_tick_ns_ - tick_ns_;
  if (next_cycle_ns_ < next_tick_ns_)
    next_cycle_ns_ += (next_tick_ns_ - next_cycle_ns_ + cycle_ns_ - 1) / cycle_ns_ * cycle_ns_;
  // What the camera did meanwhile is unknown: mapping starts again at the held pose (a
  // re-initialisation if there was a map; before the first one, events starting late, it is not).
  if (run_mapping_) {
    gap_restarts_mapping_ = mapping_.initialized();
    Reinitialise(last_tick_ns_, T_world_held_, /*keep_velocity=*/false);
  } else {
    tracker_.Reset(last_tick_ns_, T_world_held_);
  }
  return Status::Ok();
}

Status Odometry::Finish() {
  return RunTicks(TickPolicy::kEvery, /*finishing=*/true);
}

bool Odometry::ImuReady(TimeNs t_ns) const {
  // No IMU in use, or none in the input so far (a rig without one): nothing to wait for.
  if (config_.imu.mode == imu::ImuMode::kOff || !imu_seen_) return true;
  const TimeNs t_imu = t_ns + imu_offset_ns_;
  if (t_imu + kMaxImuGapNs < last_t_end_ns_) return true;  // no IMU, or a gap in its stream
  const auto first = std::lower_bound(imu_.begin(), imu_.end(), t_imu,
                                      [](const imu::ImuSample& s, TimeNs t) { return s.t_ns < t; });
  return first != imu_.end() && first->t_ns < last_t_end_ns_;
}

Status Odometry::RunTicks(TickPolicy policy, bool finishing) {
  if (policy == TickPolicy::kLatest) {
    const TimeNs until = last_t_end_ns_ - std::max<TimeNs>(0, imu_offset_ns_);
    if (next_tick_ns_ < until) {
      const int skipped = static_cast<int>((until - 1 - next_tick_ns_) / tick_ns_);
      next_tick_ns_ += skipped * tick_ns_;
      skipped_unreported_ += skipped;  // told with the next tick that runs, maybe a later call's
    }
  }
  const TimeNs gap_from_ns = last_event_ns_ + kEventGapNs;  // no tick in a gap
  while (next_tick_ns_ < last_t_end_ns_ && next_tick_ns_ <= gap_from_ns &&
         (finishing || ImuReady(next_tick_ns_))) {
    AAVIO_RETURN_IF_ERROR(Tick(next_tick_ns_, skipped_unreported_));
    skipped_unreported_ = 0;
    last_tick_ns_ = next_tick_ns_;
    next_tick_ns_ += tick_ns_;
  }
  return Status::Ok();
}

void Odometry::MeasureEdgeAge(const geometry::RigidTransform& T_world_cam,
                              const events::Observation& obs) {
  const tracking::TrackingMap* map = tracker_.map();
  if (map == nullptr) return;
  const double age_ms = tracking::MedianEdgeAgeMs(map->points_world, T_world_cam, camera_,
                                                  obs.ts_left, decay_.decay_ms());
  if (age_ms >= 0.0) decay_.AddEdgeAge(age_ms);
}

void Odometry::PublishToTracking(const mapping::LocalMapPtr& map) {
  if (!map) {
    tracker_.SetMap(nullptr);
    return;
  }
  auto tracking_map = std::make_shared<tracking::TrackingMap>();
  tracking_map->T_world_ref = map->T_world_ref;
  tracking_map->points_world = map->points_world;
  tracker_.SetMap(std::move(tracking_map));
}

// The IMU samples around (previous tick, t] in camera time: from the last at or before the
// previous tick to the first at or after t, among those before the time all data is in up to
// (others may have arrived: they are left for later ticks, so that the output does not depend
// on how the input was split).
std::vector<imu::ImuSample> Odometry::ImuWindow(TimeNs t_ns) {
  const TimeNs offset = imu_offset_ns_;
  while (imu_.size() > 2 && imu_[1].t_ns <= last_tick_ns_ + offset)
    imu_.pop_front();
  auto window_end = imu_.begin();
  while (window_end != imu_.end() && window_end->t_ns < t_ns + offset)
    ++window_end;
  if (window_end != imu_.end() && window_end->t_ns < last_t_end_ns_) ++window_end;
  std::vector<imu::ImuSample> window(imu_.begin(), window_end);
  for (imu::ImuSample& s : window)
    s.t_ns -= offset;
  return window;
}

void Odometry::Reinitialise(TimeNs t_ns, const geometry::RigidTransform& T_world_cam,
                            bool keep_velocity) {
  mapping_.Reset();  // a cycle of the old map still running is dropped
  history_.Clear();
  PublishToTracking(nullptr);
  tracker_.Reset(t_ns, T_world_cam, keep_velocity);
  inertial_check_.Restart();
  lost_ticks_ = 0;
}

Status Odometry::Tick(TimeNs t_ns, int skipped_ticks) {
  const bool cycle_due = CycleDue(t_ns);
  auto obs = std::make_shared<events::Observation>();
  OdometryTick tick;
  tick.skipped_ticks = skipped_ticks;
  AAVIO_RETURN_IF_ERROR(Observe(t_ns, cycle_due, obs.get(), &tick));
  if (before_tick) before_tick(*obs);
  AAVIO_RETURN_IF_ERROR(TakeFinishedCycle(t_ns, &tick));
  const tracking::TrackingResult tracked = Track(t_ns, *obs, &tick);
  if (!ImuContradicts(t_ns, tracked, &tick)) {
    if (tracked.status == tracking::TrackingStatus::kOk) MeasureEdgeAge(tracked.T_world_cur, *obs);
    if (run_mapping_) AAVIO_RETURN_IF_ERROR(Map(t_ns, cycle_due, obs, tracked, &tick));
  }
  if (on_tick) on_tick(tick);
  return Status::Ok();
}

bool Odometry::CycleDue(TimeNs t_ns) {
  const bool due = t_ns >= next_cycle_ns_;
  while (next_cycle_ns_ <= t_ns)
    next_cycle_ns_ += cycle_ns_;
  return due;
}

Status Odometry::Observe(TimeNs t_ns, bool cycle_due, events::Observation* obs,
                         OdometryTick* tick) {
  const bool maps_here = run_mapping_ && (!mapping_.initialized() || cycle_due);
  AAVIO_RETURN_IF_ERROR(builder_.Build(t_ns, obs,
                                       {.right_ts = maps_here || config_.tracking.stereo_check,
                                        .edges = maps_here || !run_mapping_,
                                        .decay_ms = decay_.decay_ms()}));
  ++ticks_;
  tick->t_ns = t_ns;
  tick->new_events_left = obs->new_events_left;
  tick->new_events_right = obs->new_events_right;
  tick->dropped_events = builder_.dropped_events();
  tick->representation = obs->timings;
  return Status::Ok();
}

Status Odometry::TakeFinishedCycle(TimeNs t_ns, OdometryTick* tick) {
  Expected<std::optional<MappingRunner::Cycle>> finished =
      mapping_.Collect(t_ns, &tick->mapping_wait_ms);
  if (!finished) return finished.status();
  if (*finished) ApplyCycle(**finished, tick);
  return Status::Ok();
}

void Odometry::ApplyCycle(const MappingRunner::Cycle& cycle, OdometryTick* tick) {
  tick->mapped = true;
  tick->mapping = cycle.report;
  tick->map = cycle.map;
  tick->map_observation = cycle.observation;
  if (cycle.map) PublishToTracking(cycle.map);  // none while the FIFO fills
}

tracking::TrackingResult Odometry::Track(TimeNs t_ns, const events::Observation& obs,
                                         OdometryTick* tick) {
  const std::vector<imu::ImuSample> window = ImuWindow(t_ns);
  motion_evidence_.Add(window);
  inertial_check_.AddSamples(window);
  const tracking::TrackingResult tracked =
      tracker_.Track(obs, rectification_.left.valid_mask, window);
  tick->T_world_cam = tracked.T_world_cur;
  T_world_held_ = tracked.T_world_cur;
  tick->gap_before = std::exchange(pending_gap_, std::nullopt);
  tick->reinitialised = tick->gap_before && gap_restarts_mapping_;
  tick->status = tracked.status;
  tick->lost_reason = tracked.lost_reason;
  tick->gyro_bias = tracker_.gyro_bias();
  return tracked;
}

bool Odometry::ImuContradicts(TimeNs t_ns, const tracking::TrackingResult& tracked,
                              OdometryTick* tick) {
  if (ImuUsed() && run_mapping_ && tracked.status == tracking::TrackingStatus::kOk) {
    const auto gravity =
        inertial_check_.AddTrackedPose(t_ns, tracked.T_world_cur, tracker_.gyro_bias());
    if (gravity && !gravity->agrees) {
      tick->status = tracking::TrackingStatus::kLost;
      tick->lost_reason = tracking::LostReason::kImuDisagrees;
      Reinitialise(t_ns, tick->T_world_cam, /*keep_velocity=*/false);
      tick->reinitialised = true;
      return true;
    }
  } else {
    inertial_check_.Restart();
  }
  tick->registration_iterations = tracked.registration.iterations;
  if (tracked.registered) tick->registration_stop = tracked.registration.stop;
  tick->stereo_left_out = tracked.stereo_left_out;
  tick->tracking_ms = tracked.prediction_ms + tracked.registration_ms;
  tick->prediction_ms = tracked.prediction_ms;
  tick->imu_state = tracker_.imu_state();
  return false;
}

Status Odometry::Map(TimeNs t_ns, bool cycle_due, const std::shared_ptr<events::Observation>& obs,
                     const tracking::TrackingResult& tracked, OdometryTick* tick) {
  const mapping::PosedObservation now{obs, tracked.T_world_cur};
  if (!mapping_.initialized()) {
    AAVIO_RETURN_IF_ERROR(Bootstrap(now, tick));
  } else if (tracked.status == tracking::TrackingStatus::kOk) {
    lost_ticks_ = 0;
    if (cycle_due) {
      Expected<std::optional<MappingRunner::Cycle>> ran = mapping_.Start(
          t_ns, now, history_.PartnersFor(tracked.T_world_cur), &tick->mapping_skipped);
      if (!ran) return ran.status();
      if (*ran) ApplyCycle(**ran, tick);
    }
  } else if (tracked.status == tracking::TrackingStatus::kImuOnly) {
    // Carried on the IMU through a stretch without events: the map is kept for when they return.
  } else if (++lost_ticks_ >= config_.pipeline.max_lost_ticks) {
    // Lost for too long (ticks without events too: the camera may have moved meanwhile, and the
    // gyroscope alone does not say how far): forget the map; the next ticks bootstrap at the
    // held pose.
    Reinitialise(t_ns, tracked.T_world_cur, /*keep_velocity=*/true);
    tick->reinitialised = true;
  }
  // This tick's AA map and tracked pose: a later cycle's temporal partner (partners are earlier
  // mapping ticks, as in the reference's queue of mapping frames).
  if (!obs->aa_map.empty() && (tracked.status == tracking::TrackingStatus::kOk || tick->bootstrap))
    history_.Remember(now);
  return Status::Ok();
}

Status Odometry::Bootstrap(const mapping::PosedObservation& now, OdometryTick* tick) {
  // SGM on this tick at the current pose; too few points: try the next tick. A small first map
  // needs the IMU to show motion, if there is an IMU.
  const Status init = mapping_.Initialize(now, !ImuUsed() || motion_evidence_.Moving());
  if (init.code() == StatusCode::kFailedPrecondition) {
    tick->bootstrap_failure = init.message();
    return Status::Ok();
  }
  AAVIO_RETURN_IF_ERROR(init);
  tick->mapped = tick->bootstrap = true;
  tick->map = mapping_.local_map();
  tick->map_observation = now.obs;
  PublishToTracking(tick->map);
  MeasureEdgeAge(now.T_world_obs, *now.obs);  // the first map's own edges, as they are now
  lost_ticks_ = 0;
  return Status::Ok();
}

}  // namespace aavio::pipeline
