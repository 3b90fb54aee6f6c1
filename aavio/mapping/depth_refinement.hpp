#pragma once
/// Depth refinement and uncertainty (docs/mapping.md): for each match a 1-D Levenberg–Marquardt
/// on ρ of the Student-t-weighted patch residual — left TS minus right TS at the disparity of ρ
/// for static matches; current AA minus past AA at the epipolar position of ρ for temporal ones
/// (the paper's temporal residual on AA maps, as ESVO2 evaluates it). Uncertainty from the
/// Jacobian: σ_ρ² = σ_t² / JᵀJ, σ_t² = ν/(ν − 2) s_t². At most 10 steps ([ICRA code], [ESVO]; the
/// patch is static stereo's 15×7). Estimates failing the culling rules (§4.7) are dropped.

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/mapping/depth_point.hpp"
#include "aavio/mapping/mapping_config.hpp"

namespace aavio::mapping {

struct RefinementInput {
  const cv::Mat& left_ts;            ///< CV_32FC1, for static matches
  const cv::Mat& right_ts;           ///< CV_32FC1
  const cv::Mat* aa_now = nullptr;   ///< CV_32FC1, for temporal matches
  const cv::Mat* aa_past = nullptr;  ///< CV_32FC1
  geometry::RigidTransform T_past_now;
};

/// Temporal estimates' own culling thresholds (temporal_stereo's keys of the same names); 0:
/// refinement's.
struct TemporalCulls {
  double max_inv_depth_stddev = 0.0;
  double residual_threshold = 0.0;
};

/// Culling by `refinement`'s thresholds (temporal estimates by `temporal`'s where it sets them)
/// and by the inverse-depth `range`.
std::vector<DepthPoint> RefineDepths(const RefinementInput& input, std::span<const Match> matches,
                                     const RectifiedStereo& stereo,
                                     const DepthRefinementConfig& refinement,
                                     TemporalCulls temporal, InvDepthRange range);

/// The robust scale of residuals by the Student-t IRLS loop (start s², iterate until the change
/// is below 5 %), and the weights w_k = (ν + 1)/(ν + r_k²/s²).
double StudentTScale2(std::span<const float> residuals, double nu, double s2_start);

}  // namespace aavio::mapping
