#pragma once
/// Depth maps scored against a sequence's ground-truth depth (docs/evaluation.md), as they are made
/// or as they were written: each map against the ground-truth frame nearest in time (within 25 ms),
/// seen from the camera's true pose at that frame, the map placed by the true pose at its own
/// time — so the score is the map's, not the trajectory's.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "aavio/eval/depth_error.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/recording/run_evaluation.hpp"

namespace aavio::recording {

/// A map is scored against a ground-truth frame at most this far from it in time.
inline constexpr TimeNs kDepthMatchWindowNs = 25 * kNsPerMs;

class DepthScorer {
 public:
  /// Reads the ground truth's depth index; `gt_poses` must cover the maps' times.
  static Expected<DepthScorer> Create(const RunGroundTruth& truth,
                                      const std::vector<geometry::StampedPose>& gt_poses);

  struct Frame {
    io::GtDepthFrame frame;
    geometry::RigidTransform T_world_cam;  ///< the true pose at the frame's time
  };
  /// The ground-truth frame nearest `t_ns` (within kDepthMatchWindowNs), loaded, with its true
  /// pose; nullopt where there is none, or no true pose.
  Expected<std::optional<Frame>> Nearest(TimeNs t_ns) const;

  /// A map whose points are in the true world (a run on ground-truth poses). False: no frame.
  Expected<bool> AddInWorld(TimeNs t_ns, const std::vector<Eigen::Vector3d>& points_world);
  /// The same against a frame found with Nearest.
  void AddInWorld(const Frame& frame, const std::vector<Eigen::Vector3d>& points_world);
  /// A depth image of the rectified left camera at `t_ns` (metres, CV_32FC1, 0 = none), e.g. a
  /// disparity map of a run turned into depth. False: no frame or no true pose at `t_ns`.
  Expected<bool> AddDepthImage(TimeNs t_ns, const cv::Mat& depth_m);

  const eval::DepthErrorAccumulator& accumulator() const { return accumulator_; }
  /// Keep every scored point (eval::DepthErrorAccumulator::KeepPoints).
  void KeepPoints(bool keep) { accumulator_.KeepPoints(keep); }
  const RunGroundTruth& truth() const { return truth_; }

 private:
  DepthScorer(RunGroundTruth truth, geometry::PoseBuffer poses,
              std::vector<io::GtDepthEntry> frames)
      : truth_(std::move(truth)),
        poses_(std::move(poses)),
        frames_(std::move(frames)),
        accumulator_(truth_.camera) {}

  RunGroundTruth truth_;
  geometry::PoseBuffer poses_;
  std::vector<io::GtDepthEntry> frames_;
  eval::DepthErrorAccumulator accumulator_;
};

}  // namespace aavio::recording
