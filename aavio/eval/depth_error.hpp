#pragma once
/// Depth accuracy of a map against ground truth (docs/evaluation.md): for every estimated point
/// with ground truth, |z_est − z_gt| (mean, median) and |Δz| / z_gt (mean relative); completeness =
/// share of ground-truth edge pixels with an estimate within one pixel, overall and split into
/// near-horizontal edges and the others. Points on a depth discontinuity (a ground-truth depth
/// within one pixel differs by more than `kDiscontinuityRatio`) are also scored apart, as the
/// "disc" regions of the Middlebury and KITTI stereo benchmarks: there a sub-pixel shift of the
/// point decides between foreground and background depth. Block coverage = share of the image's
/// `kCoverageBlockPx`-square blocks that hold structure (at least `kCoverageBlockPx` ground-truth
/// edge pixels: an edge across the block) and at least one estimate: how much of the scene's
/// structure the map reaches at all, which pixel completeness, bounded by the number of points,
/// does not tell (a map of 2.5k well-spread points against one of 10k on the strongest edges).
/// The same figures up to depth cutoffs (the event-stereo depth benchmarks' 10 / 20 / 30 m, as on
/// MVSEC and DSEC) say where in depth a map reaches the scene: points and edge pixels whose
/// ground-truth depth is at most the cutoff.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "aavio/geometry/rigid_transform.hpp"

namespace aavio::eval {

/// A rectified pinhole camera: the one ground-truth depth maps are drawn in. With the stereo
/// pair's f·b the errors are also given in disparity, which does not grow with the scene's depth.
struct PinholeCamera {
  int width = 0, height = 0;
  double f = 0.0, cx = 0.0, cy = 0.0;
  double fb_px_m = 0.0;  ///< focal length × baseline [px·m]; 0: no disparity errors
};

/// A pixel is on a depth discontinuity when the largest and the smallest ground-truth depth of
/// its 3×3 neighbourhood differ by more than this factor.
inline constexpr double kDiscontinuityRatio = 1.1;

/// Side of the blocks of the block coverage [px], and the number of edge pixels that give a block
/// structure.
inline constexpr int kCoverageBlockPx = 16;

/// Ground-truth depth cutoffs [m] of the per-cutoff figures.
inline constexpr std::array<double, 3> kDepthCutoffsM = {10.0, 20.0, 30.0};

/// Error and completeness over the points and edge pixels up to one depth cutoff.
struct DepthCutoffSummary {
  double max_depth_m = 0.0;
  std::size_t points = 0;     ///< estimates whose ground-truth depth is within the cutoff
  double mean_m = 0.0;        ///< mean |Δz| of those
  double relative = 0.0;      ///< mean |Δz| / z_gt of those
  double completeness = 0.0;  ///< of the edge pixels within the cutoff
  double completeness_horizontal = 0.0;  ///< of the near-horizontal ones
};

struct DepthErrorSummary {
  std::size_t points = 0;  ///< estimates with ground truth
  std::size_t frames = 0;
  double mean_m = 0.0, median_m = 0.0;
  double relative = 0.0;         ///< mean of |Δz| / z_gt
  double relative_median = 0.0;  ///< median of |Δz| / z_gt
  double outliers = 0.0;         ///< share of points with |Δz| / z_gt > 10 %
  /// Mean true depth of the scored points: the paper's Table III "depth range". The relative
  /// error of a matcher with a given disparity error grows in proportion to it.
  double mean_true_depth_m = 0.0;
  /// |f·b / z_est − f·b / z_gt| [px], mean and median (0 without f·b).
  double disparity_error_px = 0.0, disparity_error_median_px = 0.0;
  double completeness = 0.0;  ///< share of edge pixels with an estimate (±1 px)
  double completeness_horizontal = 0.0;
  double completeness_other = 0.0;
  double block_coverage = 0.0;        ///< share of blocks with structure holding an estimate
  std::size_t points_horizontal = 0;  ///< estimates on near-horizontal GT edges
  double relative_horizontal = 0.0;
  std::size_t points_discontinuity = 0;  ///< estimates on a GT depth discontinuity
  double relative_discontinuity = 0.0;   ///< mean relative error of those
  double relative_continuous = 0.0;      ///< mean relative error of all the others
  std::array<DepthCutoffSummary, kDepthCutoffsM.size()> cutoffs{};
};

/// One scored estimate, where it fell in the ground-truth frame (kept on request, for plots).
struct ScoredDepthPoint {
  static constexpr std::uint8_t kDiscontinuity = 1;  ///< on a ground-truth depth discontinuity
  static constexpr std::uint8_t kHorizontal = 2;     ///< on a near-horizontal ground-truth edge
  float u = 0.0f, v = 0.0f;                          ///< pixel of the ground-truth frame
  float z_gt_m = 0.0f, z_est_m = 0.0f;
  std::uint8_t kind = 0;    ///< kDiscontinuity | kHorizontal
  std::uint32_t frame = 0;  ///< the how-manieth Add it came from (0 first)
};

class DepthErrorAccumulator {
 public:
  explicit DepthErrorAccumulator(const PinholeCamera& camera) : camera_(camera) {}

  /// Keep every scored point (points()) from now on; off by default: a long run scores millions.
  void KeepPoints(bool keep) { keep_points_ = keep; }
  const std::vector<ScoredDepthPoint>& points() const { return points_; }

  /// One map (points in the world) against one ground-truth frame (depth CV_32F and edge labels
  /// CV_8U, may be empty) seen from T_world_cam.
  void Add(const std::vector<Eigen::Vector3d>& points_world, const cv::Mat& gt_depth_m,
           const cv::Mat& gt_edges, const geometry::RigidTransform& T_world_cam);

  DepthErrorSummary Summary() const;
  /// |Δz| [m] and |Δz| / z_gt of every scored point, in the order added (for histograms).
  const std::vector<double>& errors_m() const { return errors_; }
  const std::vector<double>& relative_errors() const { return relative_; }

 private:
  /// Block coverage of one map: `covered` marks the pixels holding an estimate (undilated).
  void CountBlocks(const cv::Mat& covered, const cv::Mat& gt_edges);

  PinholeCamera camera_;
  bool keep_points_ = false;
  std::vector<ScoredDepthPoint> points_;
  std::vector<double> errors_, relative_, disparity_errors_;
  double true_depth_sum_ = 0.0;
  double relative_horizontal_sum_ = 0.0;
  std::size_t horizontal_points_ = 0;
  double relative_discontinuity_sum_ = 0.0;
  std::size_t discontinuity_points_ = 0;
  std::size_t edges_ = 0, edges_covered_ = 0;
  std::size_t horizontal_edges_ = 0, horizontal_covered_ = 0;
  std::size_t blocks_ = 0, blocks_covered_ = 0;
  std::size_t frames_ = 0;
  /// Per depth cutoff: sums over the points and counts of the edge pixels within it.
  struct CutoffCounts {
    std::size_t points = 0;
    double error_sum = 0.0, relative_sum = 0.0;
    std::size_t edges = 0, edges_covered = 0, horizontal = 0, horizontal_covered = 0;
  };
  std::array<CutoffCounts, kDepthCutoffsM.size()> cutoffs_{};
};

}  // namespace aavio::eval
