#pragma once
/// Where and when the odometry's mapping cycles run, around a mapping::Mapper that only this
/// class touches (pipeline.concurrent_mapping, pipeline.real_time):
///   inline      each cycle runs inside its tick; its map is tracked from the next tick on.
///   concurrent  (default) a cycle runs on a thread of its own while the following ticks are
///               tracked; its map reaches tracking at the next cycle's tick, waited for if need
///               be — the lag is fixed in data time, so the output stays bit-reproducible.
///   real time   as concurrent, but a map reaches tracking at the first tick after it is done, and
///               a cycle due while the last still runs is skipped (for live input: not
///               reproducible).
/// The bootstrap (SGM) runs on the caller's thread: before the first map no cycle runs.

#include <future>
#include <optional>

#include "aavio/common/status.hpp"
#include "aavio/mapping/mapper.hpp"
#include "aavio/mapping/temporal_partners.hpp"
#include "aavio/pipeline/odometry_config.hpp"

namespace aavio::pipeline {

class MappingRunner {
 public:
  enum class Mode { kInline, kConcurrent, kRealTime };
  static Mode ModeOf(const PipelineConfig& config);

  /// `cycle_ns`: the mapping period (a concurrent cycle's map reaches tracking that much later).
  MappingRunner(const mapping::RectifiedStereo& stereo, const cv::Mat& valid_mask,
                const mapping::MappingConfig& config, Mode mode, TimeNs cycle_ns);
  ~MappingRunner();  ///< waits for a cycle still running
  MappingRunner(const MappingRunner&) = delete;
  MappingRunner& operator=(const MappingRunner&) = delete;

  /// What a cycle gave.
  struct Cycle {
    mapping::MappingCycleReport report;
    mapping::LocalMapPtr map;                                ///< the map it published, if it did
    std::shared_ptr<const events::Observation> observation;  ///< the map's observation
  };

  /// At the tick t_ns, before it is tracked: the cycle whose map reaches tracking now, if any
  /// (concurrent: the one started a cycle ago, waited for — `waited_ms` says how long; real
  /// time: one that finished meanwhile). A cycle's error is returned here.
  Expected<std::optional<Cycle>> Collect(TimeNs t_ns, double* waited_ms);

  /// A cycle due at the tick t_ns on `now`: inline it runs here and is returned; otherwise it
  /// starts on a thread (nothing returned), or is skipped while the last one still runs
  /// (`*skipped`).
  Expected<std::optional<Cycle>> Start(TimeNs t_ns, const mapping::PosedObservation& now,
                                       mapping::TemporalHistory::Partners partners, bool* skipped);

  bool initialized() const { return mapper_.initialized(); }
  /// The first map (mapping::Mapper::Initialize); on success it is local_map().
  Status Initialize(const mapping::PosedObservation& now, bool small_map_ok) {
    return mapper_.Initialize(now, small_map_ok);
  }
  mapping::LocalMapPtr local_map() const { return mapper_.local_map(); }
  /// Forgets the map; a cycle still running is waited for and its result dropped.
  void Reset();

 private:
  Cycle RunCycle(const mapping::PosedObservation& now,
                 const mapping::TemporalHistory::Partners& partners, Status* status);

  mapping::Mapper mapper_;
  Mode mode_;
  TimeNs cycle_ns_;
  struct Pending {
    Status status = Status::Ok();
    Cycle cycle;
  };
  std::future<Pending> pending_;
  TimeNs pending_t_ns_ = 0;  // the tick the pending cycle was started on
};

}  // namespace aavio::pipeline
