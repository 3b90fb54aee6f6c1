#pragma once
/// The most a map could cover, given its edge samples: every sample of the mapping cycles a map
/// fuses, at its true depth in the cells fusion gives an estimate (the 2×2 or 3×3 pixels from
/// the sample's floor; mapping::DepthMap::Fuse), scored like the map (DepthErrorAccumulator:
/// completeness, near-horizontal completeness, block coverage). Between this ceiling and the map's
/// own figures lies what matching, refinement, culling and cleaning lose; between it and 100 %,
/// what the sampling never offered (edges without events, samples elsewhere). It says, for
/// instance, how much near-horizontal completeness temporal stereo could add at most on a sequence.

#include <Eigen/Core>
#include <deque>
#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/eval/depth_error.hpp"
#include "aavio/geometry/rigid_transform.hpp"

namespace aavio::eval {

class SampleCeiling {
 public:
  /// Samples whose true depth lies outside [min_depth_m, max_depth_m] (the mapping's search
  /// range) are left out: no matcher could place them. `cell_side` is 2 or 3: the side of the
  /// block of pixels a fused estimate occupies (mapping.fusion.radius 0 or ≥ 1).
  SampleCeiling(const PinholeCamera& camera, double min_depth_m, double max_depth_m, int cell_side);

  /// One mapping cycle's samples (rectified pixels), seen from T_world_cam with ground-truth
  /// depth `gt_depth_m` (CV_32F, the frame of the cycle's time).
  void AddCycle(std::span<const Eigen::Vector2f> samples_px, const cv::Mat& gt_depth_m,
                const geometry::RigidTransform& T_world_cam);
  /// Scores the samples of the newest `cycles` cycles (as many as the scored map fuses) against
  /// a ground-truth frame, as DepthErrorAccumulator::Add does a map.
  void Score(std::size_t cycles, const cv::Mat& gt_depth_m, const cv::Mat& gt_edges,
             const geometry::RigidTransform& T_world_cam);
  /// Forgets the stored cycles (a re-initialised map starts again).
  void Clear() { cycles_.clear(); }

  DepthErrorSummary Summary() const { return scored_.Summary(); }

 private:
  PinholeCamera camera_;
  double min_depth_m_, max_depth_m_;
  int cell_lo_;  ///< the cells of a sample at (u, v): floor + [cell_lo_, 1] in both directions
  std::deque<std::vector<Eigen::Vector3d>> cycles_;  ///< points in the world, newest at the back
  DepthErrorAccumulator scored_;
};

}  // namespace aavio::eval
