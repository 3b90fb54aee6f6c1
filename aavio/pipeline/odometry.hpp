#pragma once
/// The odometry front-end (docs/architecture.md): events and IMU in; a pose
/// every tick, a local map every mapping cycle, and their timings out. Synchronous and driven by
/// data time only — the same input and seed give the same output, bit for bit, whatever the machine
/// load.
///
/// At every tick (time_surface.rate_hz): build the Observation; track it against the newest local
/// map (gyroscope or constant-velocity prediction, time-surface registration). Every
/// rate_hz/mapping.rate_hz ticks, map on that same observation at its tracked pose (static +
/// temporal stereo, fusion) and hand the new map to tracking — the reference's chain, where
/// mapping uses the newest observation with a known pose, without its wall-clock waits.
/// With `pipeline.concurrent_mapping` (default) the cycle runs on a second thread while the
/// following ticks are tracked, and its map reaches tracking at the next cycle's tick (a lag fixed
/// in data time, so still deterministic); `pipeline.real_time` hands maps over whenever they are
/// done and skips cycles while one runs (not deterministic).
/// Before the first map, mapping bootstraps with SGM at the current pose (the start pose, turned
/// by the gyroscope). After `pipeline.max_lost_ticks` lost ticks in a row, mapping is reset and
/// bootstraps again at the held pose (the last good pose carried forward by the gyroscope),
/// never back at the origin.
///
/// Tracking alone (`run_mapping` false): no mapping, no bootstrap; the caller hands maps in with
/// SetTrackingMap (e.g. from `before_tick`, built from ground truth) — tracking measured on its
/// own.

#include <deque>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "aavio/events/representation_builder.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/imu/inertial_check.hpp"
#include "aavio/imu/motion_evidence.hpp"
#include "aavio/mapping/temporal_partners.hpp"
#include "aavio/pipeline/mapping_runner.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "aavio/tracking/edge_age.hpp"
#include "aavio/tracking/tracker.hpp"

namespace aavio::pipeline {

/// A stretch of data time in which neither camera gave a single event for at least
/// Odometry::kEventGapNs: a gap in the recording (no real sensor is that silent; its noise alone
/// gives thousands of events a second). Its ticks are not run.
struct EventGap {
  TimeNs from_ns = 0;  ///< the last event before it (the start, for a gap before the first)
  TimeNs to_ns = 0;    ///< the first event after it
};

/// What one tick produced.
struct OdometryTick {
  TimeNs t_ns = 0;
  geometry::RigidTransform T_world_cam;  ///< rectified left camera
  tracking::TrackingStatus status = tracking::TrackingStatus::kNoMap;
  tracking::LostReason lost_reason = tracking::LostReason::kNone;
  int registration_iterations = 0;
  /// Why the registration's LM stopped, where it ran.
  std::optional<tracking::RegistrationStop> registration_stop;
  int stereo_left_out = 0;   ///< map points tracking.stereo_check left out of the registration
  double tracking_ms = 0.0;  ///< prediction + registration
  double prediction_ms = 0.0;
  events::RepresentationTimings representation;
  bool mapped = false;     ///< a mapping cycle ran on this tick
  bool bootstrap = false;  ///< ... and it was an SGM (re-)initialisation that succeeded
  /// A (re-)initialisation was tried on this tick and found too few points: why (it is tried
  /// again on the next tick).
  std::string bootstrap_failure;
  bool reinitialised = false;  ///< tracking was lost too long: mapping was reset here
  /// The first tick after an event gap: the gap, whose ticks were not run (mapping restarted;
  /// `reinitialised` if a map was thrown away).
  std::optional<EventGap> gap_before;
  /// Ticks due before this one that were not run (TickPolicy::kLatest: a live input catching
  /// up); their events are in this tick's time surfaces.
  int skipped_ticks = 0;
  /// Events of each camera since the previous tick.
  std::int64_t new_events_left = 0, new_events_right = 0;
  /// Events dropped so far, both cameras, because more than pipeline.max_buffered_events
  /// waited for one tick (a running total).
  std::int64_t dropped_events = 0;
  bool mapping_skipped = false;         ///< real-time mode: a cycle was due but the last still ran
  double mapping_wait_ms = 0.0;         ///< concurrent mapping: waited this long for the last cycle
  mapping::MappingCycleReport mapping;  ///< of the cycle, if one ran (not for bootstraps)
  mapping::LocalMapPtr map;             ///< the map published on this tick, if any
  /// The observation that map was made on (its time surfaces: the depth map's background).
  std::shared_ptr<const events::Observation> map_observation;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  ///< the bias the tick's prediction used
  /// imu.mode=full, once the back-end has solved a window: its biases, velocity and gravity.
  std::optional<imu::ImuState> imu_state;
};

/// Which of the ticks due in one Process call run.
enum class TickPolicy {
  kEvery,   ///< all of them, in order (files, and live input that keeps up)
  kLatest,  ///< only the last; the others are skipped and counted (live input that fell behind)
};

class Odometry {
 public:
  /// `T_world_start`: the pose at `start_ns` (identity: the world is the first camera frame).
  Odometry(const geometry::StereoRig& rig, const OdometryConfig& config, TimeNs start_ns,
           const geometry::RigidTransform& T_world_start = {}, bool run_mapping = true);

  /// Adds both cameras' events and the IMU samples of [.., t_end_ns) (each time-ordered; IMU
  /// samples in the IMU's clock) and runs the ticks due by then (all, or with kLatest the last);
  /// each goes to `on_tick`. Once IMU samples come in, a tick at t waits for the one at or after
  /// t + the IMU time offset (up to 50 ms longer: then it runs without), until the next call or
  /// Finish. How the data is split into calls does not change the output.
  Status Process(std::span<const events::Event> left, std::span<const events::Event> right,
                 std::span<const imu::ImuSample> imu, TimeNs t_end_ns,
                 TickPolicy policy = TickPolicy::kEvery);
  /// End of input: runs the ticks before the last t_end_ns still waiting for IMU samples.
  Status Finish();
  /// The time of the next tick due.
  TimeNs next_tick_ns() const { return next_tick_ns_; }

  std::function<void(const OdometryTick&)> on_tick;
  /// Called with each tick's observation before it is tracked.
  std::function<void(const events::Observation&)> before_tick;
  /// Tracking alone: the map the next ticks track against.
  void SetTrackingMap(std::shared_ptr<const tracking::TrackingMap> map) {
    tracker_.SetMap(std::move(map));
  }
  std::int64_t ticks() const { return ticks_; }
  /// Ticks run through this much data time without an event (darkness, a standstill with an
  /// ideal sensor: the pose holds); beyond it they stop, and when events return mapping restarts
  /// at the held pose on the same tick grid.
  static constexpr TimeNs kEventGapNs = 5 * kNsPerS;

  /// Wall time the last Process call spent adding events to the representations.
  double last_insertion_ms() const { return last_insertion_ms_; }
  ~Odometry();

 private:
  Status Tick(TimeNs t_ns, int skipped_ticks);
  // Runs the ticks due (all, or with kLatest the last), none past the event gap's start.
  Status RunTicks(TickPolicy policy, bool finishing);
  // Events return at resume_ns after a gap: the ticks before it run, the tick grid moves on to
  // resume_ns, mapping restarts at the held pose.
  Status SkipEventGap(TimeNs resume_ns);
  // The IMU samples the tick at t_ns needs are in: up to the first at or after t + offset.
  bool ImuReady(TimeNs t_ns) const;
  // The IMU samples of the tick at t_ns, in camera time.
  std::vector<imu::ImuSample> ImuWindow(TimeNs t_ns);
  void PublishToTracking(const mapping::LocalMapPtr& map);
  // Mapping forgets its map and tracking restarts at the held pose (lost too long, or the
  // tracked motion disagreed with the accelerometer).
  void Reinitialise(TimeNs t_ns, const geometry::RigidTransform& T_world_cam, bool keep_velocity);
  // The age of the events at the map's edges seen from T_world_cam, for the next ticks' decay.
  void MeasureEdgeAge(const geometry::RigidTransform& T_world_cam, const events::Observation& obs);
  // The steps of a tick.
  // Whether a mapping cycle is due at t_ns (on a fixed grid of data time); moves the grid on.
  bool CycleDue(TimeNs t_ns);
  // The tick's observation: the right time surface, AA map and samples only where mapping may
  // run (a bootstrap or a cycle's tick; or where a ground-truth map is built from the samples).
  Status Observe(TimeNs t_ns, bool cycle_due, events::Observation* obs, OdometryTick* tick);
  // A finished mapping cycle's map goes to tracking.
  Status TakeFinishedCycle(TimeNs t_ns, OdometryTick* tick);
  void ApplyCycle(const MappingRunner::Cycle& cycle, OdometryTick* tick);
  // Prediction and registration against the newest map.
  tracking::TrackingResult Track(TimeNs t_ns, const events::Observation& obs, OdometryTick* tick);
  // A tracked pose the accelerometer contradicts is lost, and the map that misled it goes:
  // returns true then (the tick says so).
  bool ImuContradicts(TimeNs t_ns, const tracking::TrackingResult& tracked, OdometryTick* tick);
  // Mapping on the tracked tick: the first map (bootstrap), a cycle when due, or, lost too long,
  // a re-initialisation.
  Status Map(TimeNs t_ns, bool cycle_due, const std::shared_ptr<events::Observation>& obs,
             const tracking::TrackingResult& tracked, OdometryTick* tick);
  Status Bootstrap(const mapping::PosedObservation& now, OdometryTick* tick);
  // IMU samples are in the input and the configuration uses them.
  bool ImuUsed() const { return config_.imu.mode != imu::ImuMode::kOff && imu_seen_; }

  OdometryConfig config_;
  geometry::StereoRectification rectification_;
  mapping::RectifiedStereo stereo_;
  events::RepresentationBuilder builder_;
  tracking::Tracker tracker_;
  tracking::Camera camera_;
  tracking::AdaptiveDecay decay_;
  MappingRunner mapping_;
  mapping::TemporalHistory history_;     // the mapping ticks' AA maps and poses: temporal partners
  std::deque<imu::ImuSample> imu_;       // IMU clock
  TimeNs imu_offset_ns_;                 // t_imu − t_cam
  TimeNs last_t_end_ns_;                 // all data is in up to here
  bool imu_seen_ = false;                // any IMU sample in the input so far
  imu::MotionEvidence motion_evidence_;  // for the first map: is the camera moving?
  imu::InertialCheck inertial_check_;    // does the tracked motion agree with the accelerometer?
  TimeNs tick_ns_, next_tick_ns_;
  int skipped_unreported_ = 0;  // ticks shed (TickPolicy::kLatest) no run tick has told yet
  TimeNs last_tick_ns_;         // the last tick run (the start before the first)
  TimeNs cycle_ns_;             // mapping period: a whole number of ticks
  TimeNs next_cycle_ns_;        // the next mapping cycle is due at the first tick at or after it
  bool run_mapping_;
  std::int64_t ticks_ = 0;
  int lost_ticks_ = 0;
  TimeNs last_event_ns_;                   // the newest event of either camera (the start before)
  std::optional<EventGap> pending_gap_;    // for the next tick's gap_before
  bool gap_restarts_mapping_ = false;      // ... and whether it threw a map away
  geometry::RigidTransform T_world_held_;  // the last tick's pose: where a gap's ticks resume
  double last_insertion_ms_ = 0.0;
};

}  // namespace aavio::pipeline
