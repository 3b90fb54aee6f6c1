#pragma once
/// Streaming use of the odometry (docs/api.md): push each camera's events and the IMU
/// samples as a driver delivers them — from any thread, in packets of any size — and receive every
/// tick's pose, and each new local map, through `on_tick`.
///
/// A tick runs once every stream has delivered its data up to the tick's time: a stream's
/// *watermark* is its newest event or sample, or the time a driver says it is complete up to
/// (an event packet's header stamp, so a camera that sees nothing does not hold the others up).
///
/// Two modes:
///   reproducible (default)  the ticks run inside the Push calls, on the caller's thread; the
///                           output is that of `aavio run` on the same data, bit for bit,
///                           however the data was split into packets.
///   real time               the ticks run on a thread of their own and Push never waits. When
///                           the data waiting to be processed spans more than `max_lag_s`, the
///                           odometry catches up by tracking only the newest due tick: it sheds
///                           work, never data — every event still goes into the time surfaces —
///                           and says what it shed (OdometryTick::skipped_ticks,
///                           mapping_skipped, and stats()). Mapping cycles run beside tracking
///                           and one still running when the next is due makes that one skipped
///                           (pipeline.real_time).
///
///   auto live = LiveOdometry::Create(rig, config, t0_ns, {.real_time = true});
///   (*live)->on_tick = [](const OdometryTick& tick) { publish(tick.t_ns, tick.T_world_cam); };
///   (*live)->PushEvents(events::Camera::kLeft, left_packet, left_stamp_ns);   // driver threads
///   (*live)->PushImu(imu_samples);
///   (*live)->Finish();  // end of input: the rest is processed

#include <array>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "aavio/common/log_histogram.hpp"
#include "aavio/common/status.hpp"
#include "aavio/pipeline/odometry.hpp"

namespace aavio::pipeline {

struct LiveOptions {
  /// Run the ticks on a thread of their own and shed work when behind (not bit-reproducible:
  /// what is shed depends on the machine).
  bool real_time = false;
  /// Real time: the most data time that may wait to be processed before ticks are skipped [s].
  double max_lag_s = 0.05;
  /// Wait for the IMU stream too before running a tick (false: a rig without an IMU; samples
  /// pushed anyway are still used, but then the output depends on when they arrive).
  bool wait_for_imu = true;

  Status Validate() const;
};

/// What was done with the data so far (any thread may ask).
struct LiveStats {
  std::array<std::int64_t, 2> events_pushed{};     ///< per camera (left, right)
  std::array<std::int64_t, 2> events_processed{};  ///< handed to the odometry
  std::int64_t imu_samples_pushed = 0;
  std::int64_t ticks = 0;                   ///< ticks run
  std::int64_t skipped_ticks = 0;           ///< ticks shed to catch up (real time)
  std::int64_t skipped_mapping_cycles = 0;  ///< cycles shed while the previous one ran (real time)
  double max_backlog_s = 0.0;               ///< the most data time found waiting at once
  /// From the moment the data a tick needs was all pushed (the push that completed every awaited
  /// stream up to the tick's time) to its pose reaching `on_tick` [ms], over the ticks run: what
  /// a live user waits for a pose. Within 0.5 % (LogHistogram); 0 before the first tick.
  double latency_median_ms = 0.0, latency_p99_ms = 0.0, latency_max_ms = 0.0;
};

class LiveOdometry {
 public:
  /// Checks the configuration and options; `start_ns` is the time of the first data (the world
  /// frame is the left camera's at that time).
  static Expected<std::unique_ptr<LiveOdometry>> Create(const geometry::StereoRig& rig,
                                                        const OdometryConfig& config,
                                                        TimeNs start_ns, LiveOptions options = {});
  ~LiveOdometry();  ///< stops the processing thread; data not yet processed is dropped
  LiveOdometry(const LiveOdometry&) = delete;
  LiveOdometry& operator=(const LiveOdometry&) = delete;

  /// Every tick, on the thread that runs it (set before the first Push).
  std::function<void(const OdometryTick&)> on_tick;

  /// One camera's next events (raw sensor pixels, in time order, not older than the last ones
  /// pushed). `complete_until_ns`: the stream is complete up to this time (default: the last
  /// event's). Errors name the camera and the offending time; an error of a tick run earlier
  /// on the processing thread is returned by the next Push or Finish.
  Status PushEvents(events::Camera camera, std::span<const events::Event> events,
                    std::optional<TimeNs> complete_until_ns = std::nullopt);
  /// The next IMU samples (in time order).
  Status PushImu(std::span<const imu::ImuSample> samples);
  /// End of input: runs the ticks due up to `end_ns` (default: just past the newest data of any
  /// stream) with what has arrived, and waits for them. Call it once the producers have
  /// stopped; no Push after it.
  Status Finish(std::optional<TimeNs> end_ns = std::nullopt);

  LiveStats stats() const;

 private:
  LiveOdometry(const geometry::StereoRig& rig, const OdometryConfig& config, TimeNs start_ns,
               LiveOptions options);
  /// The time every awaited stream is complete up to.
  TimeNs Horizon() const;
  /// After a push (lock held): when the horizon moved on, the wall time it did.
  void NoteHorizon();
  /// A tick's latency from the horizon's arrivals (lock held).
  void NoteLatency(TimeNs tick_ns);
  /// Takes the data before `horizon` from the queues and runs the ticks due by then (call with
  /// `lock` held; it is released while the odometry runs).
  Status ProcessUpTo(TimeNs horizon, std::unique_lock<std::mutex>& lock);
  void WorkerLoop();

  LiveOptions options_;
  TimeNs start_ns_;
  Odometry odometry_;
  mutable std::mutex mutex_;
  std::condition_variable data_ready_;
  std::array<std::vector<events::Event>, 2> events_;  // not yet processed, per camera
  std::vector<imu::ImuSample> imu_;
  std::array<TimeNs, 2> events_watermark_ns_;
  TimeNs imu_watermark_ns_;
  TimeNs processed_until_ns_;
  bool processing_ = false;  // a ProcessUpTo call runs the odometry (the lock is released)
  bool finishing_ = false;
  bool stopping_ = false;
  Status error_ = Status::Ok();
  LiveStats stats_;
  // When the horizon reached each time, the ones no tick has used yet (ticks run in time order).
  std::deque<std::pair<TimeNs, std::chrono::steady_clock::time_point>> horizon_arrivals_;
  TimeNs noted_horizon_ns_;
  LogHistogram latency_ms_;
  std::thread worker_;
};

}  // namespace aavio::pipeline
