#pragma once
/// The whole system's configuration: one section per module, composed (CONTRIBUTING.md). YAML
/// sections mirror these names; `aavio config --list` prints every key with its value.

#include <cstdint>

#include "aavio/common/config_fields.hpp"
#include "aavio/events/events_config.hpp"
#include "aavio/imu/imu_config.hpp"
#include "aavio/mapping/mapping_config.hpp"
#include "aavio/tracking/tracking_config.hpp"

namespace aavio::pipeline {

struct PipelineConfig {
  std::int64_t random_seed = 1;  ///< seeds every random choice; same seed, same trajectory
  int num_threads = 0;           ///< workers of the parallel stages (TBB, OpenCV), 0 = all cores;
                                 ///< results do not depend on it
  /// Per camera: events waiting for one tick beyond this are dropped, oldest first (counted in
  /// summary.json dropped_events); bounds memory in a burst ([ESVO] 5e6)
  int max_buffered_events = 5'000'000;
  /// Consecutive lost ticks after which mapping re-initialises (SGM) at the held pose (aavio)
  int max_lost_ticks = 5;
  /// Real-time mode (aavio): mapping cycles run on their own thread while tracking goes on; a
  /// cycle due while the previous one still runs is skipped (the newest observation wins), and a
  /// finished map reaches tracking at the next tick. For live input: which ticks are mapped and
  /// when maps arrive depends on the machine, so it is not bit-reproducible.
  bool real_time = false;
  /// Concurrent mapping (aavio; used when real_time is off): a mapping cycle runs on its own
  /// thread while the ticks up to the next cycle are tracked, and its map reaches tracking at
  /// that next cycle's tick, waiting for it if need be — the lag is fixed in data time, so the
  /// output stays bit-reproducible. Off: each cycle runs inside its tick and its map is tracked
  /// from the next tick on (one core does nothing while mapping runs on one thread).
  bool concurrent_mapping = true;

  template <typename V>
  void VisitFields(V&& v) {
    v("random_seed", random_seed, "seeds every random choice: same seed, same trajectory");
    v("num_threads", num_threads, "worker threads; 0 = all cores (results do not depend on it)");
    v("max_buffered_events", max_buffered_events,
      "events buffered per camera; the oldest are dropped beyond it");
    v("max_lost_ticks", max_lost_ticks,
      "consecutive lost ticks before mapping re-initialises at the last good pose");
    v("real_time", real_time,
      "live input: a mapping cycle still running when the next is due is skipped");
    v("concurrent_mapping", concurrent_mapping,
      "a mapping cycle runs beside the next ticks' tracking, its lag fixed in data time");
  }
  Status Validate() const;
};

struct OdometryConfig {
  PipelineConfig pipeline;
  events::TimeSurfaceConfig time_surface;
  events::AdaptiveAccumulationConfig adaptive_accumulation;
  events::EdgeSamplingConfig edge_sampling;
  mapping::MappingConfig mapping;
  tracking::TrackingConfig tracking;
  imu::ImuConfig imu;

  template <typename V>
  void VisitFields(V&& v) {
    v("pipeline", pipeline);
    v("time_surface", time_surface);
    v("adaptive_accumulation", adaptive_accumulation);
    v("edge_sampling", edge_sampling);
    v("mapping", mapping);
    v("tracking", tracking);
    v("imu", imu);
  }
  /// Every section, then the relations between sections.
  Status Validate() const;
};

/// The representation stage's part of the configuration.
events::RepresentationConfig RepresentationConfigOf(const OdometryConfig& config);

}  // namespace aavio::pipeline
