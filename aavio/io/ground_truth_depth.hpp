#pragma once
/// Ground-truth depth of a sequence (a `depth/` folder as `aavio simulate` writes it): a
/// `timestamps.txt` listing "t[s] index" lines, and per index `depth_INDEX.tiff` (metres, 32-bit
/// float, 0 = none) or, DSEC-style, `disparity_INDEX.png` (16-bit, disparity × 256, 0 = none),
/// plus optional `edges_INDEX.png` edge labels (0 none, 128 edge, 255 near-horizontal edge).
/// All in the rectified left camera.

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"

namespace aavio::io {

struct GtDepthEntry {
  TimeNs t_ns = 0;
  std::string index;
};

Expected<std::vector<GtDepthEntry>> ReadGtDepthIndex(const std::string& dir);

struct GtDepthFrame {
  TimeNs t_ns = 0;
  cv::Mat depth_m;  ///< CV_32FC1, 0 where there is no ground truth
  cv::Mat edges;    ///< CV_8UC1 labels, empty if the folder has none
};

/// Depth [m] (CV_32FC1, 0 = none) of a disparity image in the layout above (CV_16UC1, disparity
/// × 256, 0 = none): fb / (disparity − disparity_offset).
cv::Mat DepthFromDisparityImage(const cv::Mat& disparity, double fb, double disparity_offset);

/// Loads one frame; from disparity PNGs depth = fb / (disparity − offset) needs the rig's f·b
/// and principal-point offset (cx_left − cx_right).
Expected<GtDepthFrame> LoadGtDepthFrame(const std::string& dir, const GtDepthEntry& entry,
                                        double fb = 0.0, double disparity_offset = 0.0);

}  // namespace aavio::io
