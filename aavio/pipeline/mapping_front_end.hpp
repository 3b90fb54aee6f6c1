#pragma once
/// Mapping alone, driven by known poses (ground truth): events in, an Observation every tick and
/// a mapping cycle at the mapping rate, with the camera pose taken from the given PoseBuffer
/// instead of tracking — so that depth accuracy is measured on its own (issue: "a mapping-only
/// mode driven by ground-truth poses"). Synchronous and driven by data time only.

#include <functional>
#include <span>
#include <vector>

#include "aavio/events/representation_builder.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/mapping/mapper.hpp"
#include "aavio/mapping/temporal_partners.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "aavio/tracking/edge_age.hpp"

namespace aavio::pipeline {

struct MappingCycle {
  TimeNs t_ns = 0;
  bool bootstrap = false;  ///< the bootstrap map of (re-)initialisation
  mapping::MappingCycleReport report;
  events::RepresentationTimings representation;  ///< of this cycle's tick
  mapping::LocalMapPtr map;  ///< the map this cycle published, if any (see LocalMap::confirmed)
  /// The cycle's observation (its edge samples: mapping::MappingSamples).
  std::shared_ptr<const events::Observation> observation;
};

class MappingFrontEnd {
 public:
  /// `poses` holds T_world_cam of the rectified left camera over the data (it must outlive this).
  MappingFrontEnd(const geometry::StereoRig& rig, const OdometryConfig& config,
                  const geometry::PoseBuffer& poses, TimeNs start_ns);

  /// Adds both cameras' events of [.., t_end_ns) (time-ordered) and runs every tick and mapping
  /// cycle due by then; each cycle goes to `on_cycle`.
  Status Process(std::span<const events::Event> left, std::span<const events::Event> right,
                 TimeNs t_end_ns);

  std::function<void(const MappingCycle&)> on_cycle;
  /// Called at every tick (also those without mapping) with its time and timings.
  std::function<void(TimeNs, const events::RepresentationTimings&)> on_tick;

  const mapping::RectifiedStereo& stereo() const { return stereo_; }
  std::int64_t ticks() const { return ticks_; }

 private:
  Status Tick(TimeNs t_ns);

  OdometryConfig config_;
  const geometry::PoseBuffer& poses_;
  geometry::StereoRectification rectification_;
  mapping::RectifiedStereo stereo_;
  events::RepresentationBuilder builder_;
  mapping::Mapper mapper_;
  mapping::TemporalHistory history_;  // the cycles' AA maps and poses: temporal partners
  tracking::Camera camera_;
  tracking::AdaptiveDecay decay_;  // τ from the age of the events at the map's edges, as odometry
  TimeNs tick_ns_, next_tick_ns_;
  int ticks_per_cycle_;
  std::int64_t ticks_ = 0;
};

}  // namespace aavio::pipeline
