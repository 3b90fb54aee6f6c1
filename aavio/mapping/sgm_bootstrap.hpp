#pragma once
/// The first map (algorithm.md §4.12): semi-global matching (OpenCV StereoSGBM) of the rectified
/// time-surface pair, kept only at the edge samples, each point with σ_ρ = inv_depth_stddev
/// (optionally dropped when σ_ρ / ρ > bootstrap.max_relative_stddev).
/// Accepted when at least bootstrap.min_points points survive.

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/mapping/depth_point.hpp"
#include "aavio/mapping/mapping_config.hpp"

namespace aavio::mapping {

/// SGM points at the given rectified positions; an error says why there are too few.
Expected<std::vector<DepthPoint>> BootstrapWithSgm(const cv::Mat& ts_left, const cv::Mat& ts_right,
                                                   std::span<const Eigen::Vector2f> points,
                                                   const RectifiedStereo& stereo,
                                                   const MappingConfig& config);

}  // namespace aavio::mapping
