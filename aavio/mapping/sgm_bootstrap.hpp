#pragma once
/// The first map (docs/mapping.md): semi-global matching (OpenCV StereoSGBM) of the rectified
/// time-surface pair (block 11, P1 = 8·11², P2 = 32·11², uniqueness ratio 11: the reference
/// codes'), kept only at the edge samples, each point with σ_ρ = kSgmInvDepthStddev. Whether
/// they make a first map is the mapper's call (BootstrapConfig::Accepts).

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/mapping/depth_point.hpp"
#include "aavio/mapping/mapping_config.hpp"

namespace aavio::mapping {

/// σ_ρ given to every SGM point [1/m] ([ESVO], [ICRA code]).
inline constexpr double kSgmInvDepthStddev = 0.001;

/// SGM points at the given rectified positions (those with a depth in `range`).
Expected<std::vector<DepthPoint>> BootstrapWithSgm(const cv::Mat& ts_left, const cv::Mat& ts_right,
                                                   std::span<const Eigen::Vector2f> points,
                                                   const RectifiedStereo& stereo,
                                                   double student_t_nu, InvDepthRange range);

}  // namespace aavio::mapping
