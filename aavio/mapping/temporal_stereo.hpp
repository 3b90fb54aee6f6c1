#pragma once
/// Temporal stereo (docs/mapping.md): an edge pixel of the current AA map is searched in the
/// AA map of an earlier observation (both smoothed with smooth_aa), along the exact epipolar
/// segment between the projections of the nearest and farthest allowed depth (not the reference
/// code's fixed −10…70 px), with a wide flat patch (5 rows × 31 columns) suited to edges parallel
/// to the baseline; the best match under 3θ is triangulated (midpoint of the two rays) and gated by
/// depth. aavio's optional tests: enough parallax (min_parallax_px), a well-conditioned depth
/// (max_relative_depth_error), and an independent search in a second, older partner that finds the
/// same depth (cross_check_px; the two are then averaged).

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/mapping_config.hpp"
#include "aavio/mapping/rectified_stereo.hpp"

namespace aavio::mapping {

/// The matching patch ([ICRA code], hard-coded 5×31).
inline constexpr int kTemporalPatchRows = 5, kTemporalPatchCols = 31;

struct TemporalStereoInput {
  const cv::Mat& aa_now;   ///< CV_32FC1 AA map of the current observation
  const cv::Mat& aa_past;  ///< CV_32FC1 AA map of the partner observation
  const geometry::RigidTransform& T_past_now;
  /// A second, older partner for the cross-check (CV_32FC1 AA map and its pose); null = none.
  const cv::Mat* aa_check = nullptr;
  const geometry::RigidTransform* T_check_now = nullptr;
};

/// What became of a cycle's temporal candidates, one count each (summary.json
/// `mapping_per_cycle`): where they are lost says which gate to look at.
struct TemporalMatchStats {
  int matched = 0;
  /// Nothing to search: the patch is (almost) empty or leaves the image, the segment has less
  /// than `min_parallax_px` of parallax.
  int no_segment = 0;
  /// No candidate under the cost threshold (3θ), or a triangulated depth outside the gate
  /// (`min_depth_m`…`max_depth_m`).
  int no_match = 0;
  /// One pixel of matching error would move the depth by more than `max_relative_depth_error`.
  int ill_conditioned = 0;
  /// The cross-check partner found no match or another depth (`cross_check_px`).
  int check_rejected = 0;
  /// The (averaged) inverse depth fell outside the configured range.
  int out_of_range = 0;
};

/// The inverse-depth interval temporal stereo searches: the configured range ∩ the depth gate.
InvDepthRange TemporalInvDepthRange(const TemporalStereoConfig& config, InvDepthRange range);

/// Depth of a left pixel seen at `x_past` in the partner view (midpoint triangulation); ≤ 0 if
/// the rays do not meet in front of both cameras.
double TriangulateDepth(const RectifiedStereo& stereo, const Eigen::Vector2d& x_now,
                        const Eigen::Vector2d& x_past, const geometry::RigidTransform& T_past_now);

class DisparityPrediction;

/// Matches for the `points` that pass every test, in their order; `stats` (optional) counts
/// what became of each point. A match is accepted below 3 × static stereo's `zncc_threshold`
/// ([ICRA code]) and kept inside `range`. With a `prediction` (disparity_prediction.hpp) each
/// search covers the depths the previous map predicts, the whole segment where the map predicts
/// nothing there, that part of the segment leaves the image, or its best lies at a cut end.
std::vector<Match> MatchTemporal(const TemporalStereoInput& input,
                                 std::span<const Eigen::Vector2f> points,
                                 const RectifiedStereo& stereo, const TemporalStereoConfig& config,
                                 double zncc_threshold, InvDepthRange range,
                                 TemporalMatchStats* stats = nullptr,
                                 const DisparityPrediction* prediction = nullptr);

}  // namespace aavio::mapping
