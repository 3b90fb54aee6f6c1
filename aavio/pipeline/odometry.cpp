#include "aavio/pipeline/odometry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

namespace aavio::pipeline {
namespace {

// A tick waits this long past its time (plus the IMU time offset) for the IMU sample that ends its
// window; then it runs with what has arrived (no IMU stream, or a gap in it).
constexpr TimeNs kMaxImuGapNs = 50 * kNsPerMs;

tracking::Camera CameraOf(const geometry::StereoRig& rig) {
  return {rig.width(), rig.height(), rig.focal_px(), rig.cx_left(), rig.cy()};
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
               static_cast<std::uint64_t>(config.pipeline.random_seed)),
      camera_(CameraOf(rig)),
      decay_(config.time_surface.decay_ms, config.time_surface.adaptive_decay),
      mapper_(stereo_, rectification_.left.valid_mask, config.mapping),
      imu_offset_ns_(SecondsToNs(config.imu.time_offset_s)),
      last_t_end_ns_(start_ns),
      inertial_check_(rig.T_imu_rect_left().value_or(geometry::RigidTransform())),
      tick_ns_(SecondsToNs(1.0 / config.time_surface.rate_hz)),
      next_tick_ns_(start_ns + tick_ns_),
      last_tick_ns_(start_ns),
      cycle_ns_(tick_ns_ * std::max(1, static_cast<int>(std::lround(config.time_surface.rate_hz /
                                                                    config.mapping.rate_hz)))),
      next_cycle_ns_(start_ns + cycle_ns_),
      run_mapping_(run_mapping),
      last_event_ns_(start_ns),
      T_world_held_(T_world_start) {
  tracker_.Reset(start_ns, T_world_start);
}

Odometry::~Odometry() {
  if (pending_cycle_.valid()) pending_cycle_.wait();
}

// The finished cycle's map goes to tracking (with `wait`, after it finishes).
Status Odometry::CollectCycle(OdometryTick* tick, bool wait) {
  if (!pending_cycle_.valid()) return Status::Ok();
  if (!wait && pending_cycle_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return Status::Ok();
  CycleResult result = pending_cycle_.get();
  AAVIO_RETURN_IF_ERROR(result.status);
  tick->mapped = true;
  tick->mapping = result.report;
  tick->map = result.map;
  tick->map_observation = result.observation;
  if (result.map) PublishToTracking(result.map);  // none while the FIFO fills
  return Status::Ok();
}

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
    gap_restarts_mapping_ = mapper_.initialized();
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
  int skipped = 0;
  if (policy == TickPolicy::kLatest) {
    const TimeNs until = last_t_end_ns_ - std::max<TimeNs>(0, imu_offset_ns_);
    if (next_tick_ns_ < until) {
      skipped = static_cast<int>((until - 1 - next_tick_ns_) / tick_ns_);
      next_tick_ns_ += skipped * tick_ns_;
    }
  }
  const TimeNs gap_from_ns = last_event_ns_ + kEventGapNs;  // no tick in a gap
  while (next_tick_ns_ < last_t_end_ns_ && next_tick_ns_ <= gap_from_ns &&
         (finishing || ImuReady(next_tick_ns_))) {
    AAVIO_RETURN_IF_ERROR(Tick(next_tick_ns_, skipped));
    skipped = 0;
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
  if (pending_cycle_.valid()) pending_cycle_.get();  // a cycle of the old map: dropped
  mapper_.Reset();
  PublishToTracking(nullptr);
  tracker_.Reset(t_ns, T_world_cam, keep_velocity);
  inertial_check_.Restart();
  lost_ticks_ = 0;
}

Status Odometry::Tick(TimeNs t_ns, int skipped_ticks) {
  auto obs = std::make_shared<events::Observation>();
  // The right time surface, AA map and samples only where mapping may run: a bootstrap, or a
  // mapping cycle's tick (and where a ground-truth map is built from the samples, without mapping).
  // Mapping cycles are due on a fixed grid of data time (every rate_hz/mapping.rate_hz ticks).
  const bool cycle_due = t_ns >= next_cycle_ns_;
  while (next_cycle_ns_ <= t_ns)
    next_cycle_ns_ += cycle_ns_;
  const bool maps_here = run_mapping_ && (!mapper_.initialized() || cycle_due);
  AAVIO_RETURN_IF_ERROR(builder_.Build(
      t_ns, obs.get(),
      {.right_ts = maps_here, .edges = maps_here || !run_mapping_, .decay_ms = decay_.decay_ms()}));
  ++ticks_;
  OdometryTick tick;
  tick.t_ns = t_ns;
  tick.skipped_ticks = skipped_ticks;
  tick.new_events_left = obs->new_events_left;
  tick.new_events_right = obs->new_events_right;
  tick.dropped_events = builder_.dropped_events();
  tick.representation = obs->timings;
  if (before_tick) before_tick(*obs);
  if (config_.pipeline.real_time) {
    AAVIO_RETURN_IF_ERROR(CollectCycle(&tick, /*wait=*/false));
  } else if (pending_cycle_.valid() && t_ns - pending_cycle_t_ns_ >= cycle_ns_) {
    // Concurrent mapping: the cycle started one cycle ago reaches tracking now, however long
    // it took in wall time.
    const auto start = std::chrono::steady_clock::now();
    AAVIO_RETURN_IF_ERROR(CollectCycle(&tick, /*wait=*/true));
    tick.mapping_wait_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  const std::vector<imu::ImuSample> window = ImuWindow(t_ns);
  motion_evidence_.Add(window);
  inertial_check_.AddSamples(window);
  const tracking::TrackingResult tracked =
      tracker_.Track(*obs, rectification_.left.valid_mask, window);
  tick.T_world_cam = tracked.T_world_cur;
  T_world_held_ = tracked.T_world_cur;
  tick.gap_before = std::exchange(pending_gap_, std::nullopt);
  tick.reinitialised = tick.gap_before && gap_restarts_mapping_;
  tick.status = tracked.status;
  tick.lost_reason = tracked.lost_reason;
  // A tracked pose that the accelerometer contradicts is lost, and the map that misled it goes.
  const bool imu_used = config_.imu.mode != imu::ImuMode::kOff && imu_seen_;
  if (imu_used && run_mapping_ && tracked.status == tracking::TrackingStatus::kOk) {
    const auto gravity =
        inertial_check_.AddTrackedPose(t_ns, tracked.T_world_cur, tracker_.gyro_bias());
    if (gravity && !gravity->agrees) {
      tick.status = tracking::TrackingStatus::kLost;
      tick.lost_reason = tracking::LostReason::kImuDisagrees;
      tick.gyro_bias = tracker_.gyro_bias();
      Reinitialise(t_ns, tick.T_world_cam, /*keep_velocity=*/false);
      tick.reinitialised = true;
      if (on_tick) on_tick(tick);
      return Status::Ok();
    }
  } else {
    inertial_check_.Restart();
  }
  tick.registration_iterations = tracked.registration.iterations;
  tick.tracking_ms = tracked.prediction_ms + tracked.registration_ms;
  tick.prediction_ms = tracked.prediction_ms;
  tick.gyro_bias = tracker_.gyro_bias();
  tick.imu_state = tracker_.imu_state();
  if (tracked.status == tracking::TrackingStatus::kOk) MeasureEdgeAge(tracked.T_world_cur, *obs);
  if (!run_mapping_) {
    if (on_tick) on_tick(tick);
    return Status::Ok();
  }
  const mapping::PosedObservation now{obs, tracked.T_world_cur};

  if (!mapper_.initialized()) {
    // Bootstrap (SGM) on this tick at the current pose; too few points: try the next tick. A
    // small first map needs the IMU to show motion, if there is an IMU.
    const Status init = mapper_.Initialize(now, !imu_used || motion_evidence_.Moving());
    if (!init.ok() && init.code() != StatusCode::kFailedPrecondition) return init;
    if (!init.ok()) tick.bootstrap_failure = init.message();
    if (init.ok()) {
      tick.mapped = tick.bootstrap = true;
      tick.map = mapper_.local_map();
      tick.map_observation = obs;
      PublishToTracking(tick.map);
      MeasureEdgeAge(tracked.T_world_cur, *obs);  // the first map's own edges, as they are now
      lost_ticks_ = 0;
    }
  } else if (tracked.status == tracking::TrackingStatus::kOk) {
    lost_ticks_ = 0;
    if (cycle_due) {
      const mapping::Mapper::Partners partners = mapper_.TemporalPartnersFor(tracked.T_world_cur);
      const bool on_thread = config_.pipeline.real_time || config_.pipeline.concurrent_mapping;
      if (!on_thread) {
        AAVIO_RETURN_IF_ERROR(mapper_.Update(now, partners.main ? &*partners.main : nullptr,
                                             &tick.mapping,
                                             partners.check ? &*partners.check : nullptr));
        tick.mapped = true;
        if (tick.mapping.published) {
          tick.map = mapper_.local_map();
          tick.map_observation = obs;
          PublishToTracking(tick.map);
        }
      } else if (pending_cycle_.valid()) {
        tick.mapping_skipped = true;  // the last cycle still runs: this one is dropped
      } else {
        pending_cycle_t_ns_ = t_ns;
        // The partners are copies: the mapper may remember later observations meanwhile.
        pending_cycle_ = std::async(std::launch::async, [this, now, partners] {
          CycleResult r;
          r.status = mapper_.Update(now, partners.main ? &*partners.main : nullptr, &r.report,
                                    partners.check ? &*partners.check : nullptr);
          if (r.report.published) {
            r.map = mapper_.local_map();
            r.observation = now.obs;
          }
          return r;
        });
      }
    }
  } else if (tracked.status == tracking::TrackingStatus::kImuOnly) {
    // Carried on the IMU through a stretch without events: the map is kept for when they return.
  } else if (++lost_ticks_ >= config_.pipeline.max_lost_ticks) {
    // Lost for too long (ticks without events too: the camera may have moved meanwhile, and the
    // gyroscope alone does not say how far): forget the map; the next ticks bootstrap at the
    // held pose.
    Reinitialise(t_ns, tracked.T_world_cur, /*keep_velocity=*/true);
    tick.reinitialised = true;
  }

  // This tick's AA map and tracked pose: a later cycle's temporal partner (partners are earlier
  // mapping ticks, as in the reference's queue of mapping frames).
  if (!obs->aa_map.empty() && (tracked.status == tracking::TrackingStatus::kOk || tick.bootstrap))
    mapper_.Remember(now);
  if (on_tick) on_tick(tick);
  return Status::Ok();
}

}  // namespace aavio::pipeline
