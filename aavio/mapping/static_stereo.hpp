#pragma once
/// Static stereo: left/right block matching of time surfaces along rectified rows
/// (algorithm.md §4.3). For each edge pixel the left patch (15×7) is compared with right patches
/// at every disparity of the range the depth range allows, by ½(1 − ZNCC); with a coarse step
/// the disparities near good coarse costs are then searched one by one (ICRA/ESVO2 tolerances
/// 1.035θ / 1.03θ / 1.02θ).

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/mapping/mapping_config.hpp"
#include "aavio/mapping/rectified_stereo.hpp"

namespace aavio::mapping {

struct DisparityRange {
  int min = 0, max = 0;
};
/// d_min = max(⌊d(ρ_min)⌋, min_disparity), d_max = min(⌈d(ρ_max)⌉, max_disparity).
DisparityRange StaticDisparityRange(const RectifiedStereo& stereo, const MappingConfig& config);

struct StaticStereoInput {
  const cv::Mat& left;        ///< CV_32FC1 left TS (smoothed if configured)
  const cv::Mat& right;       ///< CV_32FC1 right TS
  const cv::Mat& valid_mask;  ///< CV_8UC1 rectified left valid mask
};

/// One match per point that passes (order kept); `points` are rectified left positions.
std::vector<Match> MatchStatic(const StaticStereoInput& input,
                               std::span<const Eigen::Vector2f> points,
                               const RectifiedStereo& stereo, const MappingConfig& config);

}  // namespace aavio::mapping
