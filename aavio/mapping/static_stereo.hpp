#pragma once
/// Static stereo: left/right block matching of time surfaces along rectified rows
/// (docs/mapping.md). For each edge pixel the left patch (15×7) is compared with right patches
/// at every disparity of the range the depth range allows, by ½(1 − ZNCC); the best is accepted
/// below 1.02θ (the reference codes' tolerance).

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/mapping/mapping_config.hpp"
#include "aavio/mapping/rectified_stereo.hpp"

namespace aavio::mapping {

/// The matching patch of static stereo and of depth refinement ([ESVO], [ICRA code]: 15×7).
inline constexpr int kPatchWidth = 15, kPatchHeight = 7;
/// A left patch with more than this share of empty time surface (TS < 1) is not matched.
inline constexpr double kEmptyPatchFraction = 0.95;

struct DisparityRange {
  int min = 0, max = 0;
};
/// d_min = max(⌊d(ρ_min)⌋, 0), d_max = ⌈d(ρ_max)⌉: the disparities of the depth range.
DisparityRange StaticDisparityRange(const RectifiedStereo& stereo, InvDepthRange range);

struct StaticStereoInput {
  const cv::Mat& left;        ///< CV_32FC1 left TS (smoothed if configured)
  const cv::Mat& right;       ///< CV_32FC1 right TS
  const cv::Mat& valid_mask;  ///< CV_8UC1 rectified left valid mask
};

class DisparityPrediction;

/// One match per point that passes (order kept); `points` are rectified left positions; matches
/// outside `range` are dropped. With a `prediction` (disparity_prediction.hpp) each row search
/// covers the window the previous map predicts, the whole range where the map predicts nothing
/// there, the window leaves the image, or the window's best lies at a cut end.
std::vector<Match> MatchStatic(const StaticStereoInput& input,
                               std::span<const Eigen::Vector2f> points,
                               const RectifiedStereo& stereo, const StaticStereoConfig& config,
                               InvDepthRange range,
                               const DisparityPrediction* prediction = nullptr);

}  // namespace aavio::mapping
