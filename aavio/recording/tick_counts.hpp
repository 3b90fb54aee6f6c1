#pragma once
/// What a run's ticks and mapping cycles said, counted for summary.json: the tracking status of
/// every tick and why ticks were lost, why the registration stopped, the stretches carried on
/// the IMU alone, the map points the stereo check left out, bootstraps (the first, the failed
/// attempts), re-initialisations, mapping cycles run and skipped, and the events dropped in bursts.

#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/pipeline/odometry.hpp"

namespace aavio::recording {

class TickCounts {
 public:
  /// `begin_ns`: the data time the run starts at (the IMU stretches are in seconds from it).
  explicit TickCounts(TimeNs begin_ns) : begin_ns_(begin_ns) {}

  void AddTick(const pipeline::OdometryTick& tick);
  /// A cycle of mapping on ground-truth poses.
  void AddMappingCycle(bool bootstrap) {
    ++mapping_cycles_;
    bootstraps_ += bootstrap ? 1 : 0;
  }

  /// Ticks per tracking status so far ("ok", "lost", "no_map", "imu").
  const std::map<std::string, int>& status_counts() const { return status_counts_; }
  int mapping_cycles() const { return mapping_cycles_; }
  /// Whether ticks were counted and none of them had a map: the odometry never bootstrapped, so
  /// every pose is the start pose held.
  bool NeverMapped() const;
  /// Why the last failed (re-)initialisation found too few points ("" if none failed).
  const std::string& last_bootstrap_failure() const { return last_bootstrap_failure_; }
  std::int64_t dropped_events() const { return dropped_events_; }

  /// Its keys of summary.json; `first_tick_ns`: the first tick's time, if there was one.
  void AddTo(nlohmann::json* summary, std::optional<TimeNs> first_tick_ns) const;

 private:
  TimeNs begin_ns_;
  std::map<std::string, int> status_counts_, lost_reasons_, registration_stops_;
  std::vector<std::array<double, 2>> imu_only_;  // stretches carried on the IMU alone [s]
  bool previous_imu_only_ = false;
  std::int64_t dropped_events_ = 0;  // by pipeline.max_buffered_events
  int bootstraps_ = 0, reinitialisations_ = 0, skipped_cycles_ = 0, mapping_cycles_ = 0;
  int bootstrap_failures_ = 0;
  int registered_ticks_ = 0, stereo_ticks_ = 0;  // tracking.stereo_check's
  std::int64_t stereo_left_out_ = 0;
  std::optional<TimeNs> first_bootstrap_ns_;  // data time of the first map
  std::string last_bootstrap_failure_;
};

}  // namespace aavio::recording
