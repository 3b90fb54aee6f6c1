#include "aavio/pipeline/live_odometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aavio/common/format.hpp"

namespace aavio::pipeline {
namespace {

const char* CameraName(events::Camera camera) {
  return camera == events::Camera::kLeft ? "left" : "right";
}

/// Moves the elements of `queue` older than `horizon` (they lead: the queue is time-ordered).
template <typename T>
std::vector<T> TakeBefore(std::vector<T>* queue, TimeNs horizon) {
  const auto end = std::partition_point(queue->begin(), queue->end(),
                                        [horizon](const T& x) { return x.t_ns < horizon; });
  std::vector<T> taken(queue->begin(), end);
  queue->erase(queue->begin(), end);
  return taken;
}

}  // namespace

Status LiveOptions::Validate() const {
  if (!(std::isfinite(max_lag_s) && max_lag_s > 0.0 && max_lag_s <= 10.0)) {
    return InvalidArgument(StrFormat(
        "live option max_lag_s = %g: must be in (0, 10] seconds (how much data may wait before "
        "ticks are skipped; 0.05 is a good start)",
        max_lag_s));
  }
  return Status::Ok();
}

Expected<std::unique_ptr<LiveOdometry>> LiveOdometry::Create(const geometry::StereoRig& rig,
                                                             const OdometryConfig& config,
                                                             TimeNs start_ns, LiveOptions options) {
  AAVIO_RETURN_IF_ERROR(config.Validate());
  AAVIO_RETURN_IF_ERROR(options.Validate());
  return std::unique_ptr<LiveOdometry>(new LiveOdometry(rig, config, start_ns, options));
}

namespace {
OdometryConfig WithRealTime(OdometryConfig config, bool real_time) {
  if (real_time) config.pipeline.real_time = true;
  return config;
}
}  // namespace

LiveOdometry::LiveOdometry(const geometry::StereoRig& rig, const OdometryConfig& config,
                           TimeNs start_ns, LiveOptions options)
    : options_(options),
      start_ns_(start_ns),
      odometry_(rig, WithRealTime(config, options.real_time), start_ns),
      events_watermark_ns_{start_ns, start_ns},
      imu_watermark_ns_(start_ns),
      processed_until_ns_(start_ns),
      noted_horizon_ns_(start_ns) {
  odometry_.on_tick = [this](const OdometryTick& tick) {
    {
      std::lock_guard<std::mutex> guard(mutex_);
      NoteLatency(tick.t_ns);
      ++stats_.ticks;
      stats_.skipped_ticks += tick.skipped_ticks;
      stats_.skipped_mapping_cycles += tick.mapping_skipped ? 1 : 0;
    }
    if (on_tick) on_tick(tick);
  };
  if (options_.real_time) worker_ = std::thread([this] { WorkerLoop(); });
}

LiveOdometry::~LiveOdometry() {
  {
    std::lock_guard<std::mutex> guard(mutex_);
    stopping_ = true;
  }
  data_ready_.notify_all();
  if (worker_.joinable()) worker_.join();
}

TimeNs LiveOdometry::Horizon() const {
  TimeNs horizon = std::min(events_watermark_ns_[0], events_watermark_ns_[1]);
  if (options_.wait_for_imu) horizon = std::min(horizon, imu_watermark_ns_);
  return horizon;
}

void LiveOdometry::NoteHorizon() {
  const TimeNs horizon = Horizon();
  if (horizon <= noted_horizon_ns_) return;
  noted_horizon_ns_ = horizon;
  horizon_arrivals_.emplace_back(horizon, std::chrono::steady_clock::now());
}

void LiveOdometry::NoteLatency(TimeNs tick_ns) {
  // The first arrival at or past the tick completed its data; the earlier ones no later tick
  // needs. (The last ticks of Finish may have no arrival: they count from the Finish call.)
  while (horizon_arrivals_.size() > 1 && horizon_arrivals_[1].first <= tick_ns)
    horizon_arrivals_.pop_front();
  if (!horizon_arrivals_.empty() && horizon_arrivals_.front().first < tick_ns)
    horizon_arrivals_.pop_front();
  if (horizon_arrivals_.empty()) return;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                              horizon_arrivals_.front().second)
                        .count();
  latency_ms_.Add(ms);
  stats_.latency_max_ms = std::max(stats_.latency_max_ms, ms);
}

Status LiveOdometry::PushEvents(events::Camera camera, std::span<const events::Event> events,
                                std::optional<TimeNs> complete_until_ns) {
  std::unique_lock<std::mutex> lock(mutex_);
  AAVIO_RETURN_IF_ERROR(error_);
  if (finishing_) return FailedPrecondition("LiveOdometry::PushEvents after Finish");
  const int side = camera == events::Camera::kLeft ? 0 : 1;
  TimeNs watermark = events_watermark_ns_[side];
  for (const events::Event& e : events) {
    if (e.t_ns < watermark) {
      return InvalidArgument(StrFormat(
          "LiveOdometry::PushEvents: %s event at t = %lld ns comes after t = %lld ns; push each "
          "camera's events in time order, none before the start (t = %lld ns) and none older "
          "than a time declared complete",
          CameraName(camera), static_cast<long long>(e.t_ns), static_cast<long long>(watermark),
          static_cast<long long>(start_ns_)));
    }
    watermark = e.t_ns;
  }
  if (complete_until_ns) {
    if (*complete_until_ns < watermark) {
      return InvalidArgument(StrFormat(
          "LiveOdometry::PushEvents: %s stream declared complete until t = %lld ns, before its "
          "newest event (t = %lld ns); pass the packet's end time, or nothing",
          CameraName(camera), static_cast<long long>(*complete_until_ns),
          static_cast<long long>(watermark)));
    }
    watermark = *complete_until_ns;
  }
  events_[side].insert(events_[side].end(), events.begin(), events.end());
  events_watermark_ns_[side] = watermark;
  stats_.events_pushed[side] += static_cast<std::int64_t>(events.size());
  NoteHorizon();
  if (options_.real_time) {
    lock.unlock();
    data_ready_.notify_one();
    return Status::Ok();
  }
  return ProcessUpTo(Horizon(), lock);
}

Status LiveOdometry::PushImu(std::span<const imu::ImuSample> samples) {
  std::unique_lock<std::mutex> lock(mutex_);
  AAVIO_RETURN_IF_ERROR(error_);
  if (finishing_) return FailedPrecondition("LiveOdometry::PushImu after Finish");
  TimeNs watermark = imu_watermark_ns_;
  for (const imu::ImuSample& s : samples) {
    if (s.t_ns < watermark) {
      return InvalidArgument(StrFormat(
          "LiveOdometry::PushImu: IMU sample at t = %lld ns comes after t = %lld ns; push the "
          "samples in time order, none before the start (t = %lld ns)",
          static_cast<long long>(s.t_ns), static_cast<long long>(watermark),
          static_cast<long long>(start_ns_)));
    }
    if (!s.gyro_rad_s.allFinite() || !s.accel_m_s2.allFinite()) {
      return InvalidArgument(StrFormat(
          "LiveOdometry::PushImu: the IMU sample at t = %lld ns reads a %s that is not finite "
          "(NaN or infinite); drop or repair such samples before pushing them",
          static_cast<long long>(s.t_ns), s.gyro_rad_s.allFinite() ? "specific force" : "rate"));
    }
    watermark = s.t_ns;
  }
  imu_.insert(imu_.end(), samples.begin(), samples.end());
  imu_watermark_ns_ = watermark;
  stats_.imu_samples_pushed += static_cast<std::int64_t>(samples.size());
  NoteHorizon();
  if (options_.real_time) {
    lock.unlock();
    data_ready_.notify_one();
    return Status::Ok();
  }
  return ProcessUpTo(Horizon(), lock);
}

Status LiveOdometry::ProcessUpTo(TimeNs horizon, std::unique_lock<std::mutex>& lock) {
  // Another thread already runs the odometry: it picks this data up when it is done.
  if (processing_) return Status::Ok();
  processing_ = true;
  while (error_.ok() && horizon > processed_until_ns_) {
    std::vector<events::Event> left = TakeBefore(&events_[0], horizon);
    std::vector<events::Event> right = TakeBefore(&events_[1], horizon);
    // Every IMU sample so far: a tick's window ends at the first sample at or after it, which
    // may lie past the horizon.
    std::vector<imu::ImuSample> imu;
    imu.swap(imu_);
    stats_.events_processed[0] += static_cast<std::int64_t>(left.size());
    stats_.events_processed[1] += static_cast<std::int64_t>(right.size());
    const double backlog_s = NsToSeconds(horizon - odometry_.next_tick_ns());
    stats_.max_backlog_s = std::max(stats_.max_backlog_s, backlog_s);
    const TickPolicy policy = options_.real_time && backlog_s > options_.max_lag_s
                                  ? TickPolicy::kLatest
                                  : TickPolicy::kEvery;
    processed_until_ns_ = horizon;
    lock.unlock();
    const Status status = odometry_.Process(left, right, imu, horizon, policy);
    lock.lock();
    if (!status.ok()) error_ = status;
    // Data that arrived meanwhile (from other threads) moves the horizon on.
    if (!finishing_) horizon = std::max(horizon, Horizon());
  }
  processing_ = false;
  return error_;
}

void LiveOdometry::WorkerLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    data_ready_.wait(lock, [this] {
      return stopping_ || finishing_ || Horizon() > processed_until_ns_ || !error_.ok();
    });
    if (stopping_ || finishing_ || !error_.ok()) return;
    (void)ProcessUpTo(Horizon(), lock);  // an error is kept in error_ for the next Push
  }
}

Status LiveOdometry::Finish(std::optional<TimeNs> end_ns) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (finishing_) return FailedPrecondition("LiveOdometry::Finish called twice");
  finishing_ = true;
  // The ticks Finish runs past the horizon wait from now.
  noted_horizon_ns_ = std::numeric_limits<TimeNs>::max();
  horizon_arrivals_.emplace_back(noted_horizon_ns_, std::chrono::steady_clock::now());
  lock.unlock();
  data_ready_.notify_all();
  if (worker_.joinable()) worker_.join();  // it returns between two Process calls
  lock.lock();
  AAVIO_RETURN_IF_ERROR(error_);
  TimeNs end = std::max({events_watermark_ns_[0], events_watermark_ns_[1], imu_watermark_ns_}) + 1;
  if (end_ns) end = *end_ns;
  AAVIO_RETURN_IF_ERROR(ProcessUpTo(end, lock));
  lock.unlock();              // the ticks report to stats_ under the lock
  return odometry_.Finish();  // ticks still waiting for IMU samples past the end
}

LiveStats LiveOdometry::stats() const {
  std::lock_guard<std::mutex> guard(mutex_);
  LiveStats stats = stats_;
  stats.latency_median_ms = latency_ms_.Quantile(0.5);
  stats.latency_p99_ms = latency_ms_.Quantile(0.99);
  return stats;
}

}  // namespace aavio::pipeline
