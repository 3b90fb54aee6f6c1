#pragma once
/// `aavio run --gt-map`: tracking alone, against maps built from the sequence's ground truth, and
/// scored by the relative pose error over 100 ms against the ground-truth poses. A map holds the
/// pixels mapping would reconstruct — the edge samples of the tick at a ground-truth depth frame —
/// with their true depth, placed in the world with the true pose: the map of a perfect mapper.
/// (All labelled edges would be a different map: most of them are textures that move along
/// themselves and give no events, which tracking cannot register against.)

#include <memory>
#include <vector>

#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/tracking/tracker.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {

class GroundTruthMaps {
 public:
  /// `gt_poses` must outlive this; the sequence must have ground-truth depth.
  static Expected<GroundTruthMaps> Create(const OpenedSequence& sequence,
                                          const geometry::PoseBuffer& gt_poses);
  /// A new map at the first tick at or after each ground-truth depth frame; nullptr between.
  Expected<std::shared_ptr<tracking::TrackingMap>> MapFor(const events::Observation& obs);

 private:
  GroundTruthMaps(const OpenedSequence& s, const geometry::PoseBuffer& poses,
                  std::vector<io::GtDepthEntry> index)
      : sequence_(&s), poses_(&poses), index_(std::move(index)) {}
  const OpenedSequence* sequence_;
  const geometry::PoseBuffer* poses_;
  std::vector<io::GtDepthEntry> index_;
  std::size_t next_ = 0;
};

struct RelativeError100Ms {
  double rotation_deg_rmse = 0.0, translation_m_rmse = 0.0;
  std::size_t pairs = 0;
};

/// The relative pose error over 100 ms (10 ticks) of the estimate's poses that have ground truth.
RelativeError100Ms RelativeErrorOver100Ms(const std::vector<geometry::StampedPose>& estimate,
                                          const geometry::PoseBuffer& gt_poses);

}  // namespace aavio::cli
