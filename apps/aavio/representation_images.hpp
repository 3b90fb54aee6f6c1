#pragma once
/// PNG views of an Observation, the first thing to look at when something goes wrong: time
/// surfaces, negative TS and its gradients, the AA map with its blocks, and the edge samples.

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/events/observation.hpp"

namespace aavio::cli {

/// Signed gradient image (CV_32F) as grey around 128: darker negative, brighter positive.
cv::Mat GradientImage(const cv::Mat& gradient);

/// Raw AA counts, contrast-stretched, with the block grid: green = the block froze (contrast
/// reached β), red = it kept the whole window; each block labelled with its accumulated span.
cv::Mat AaBlocksImage(const events::Observation& obs, int grid_cols, int grid_rows);

/// Samples as dots (rectified positions) over a grey rectified image.
cv::Mat SamplesImage(const cv::Mat& background, const std::vector<events::EdgeSample>& samples,
                     const cv::Scalar& colour);

/// Writes every view into `dir` (created) and returns the file names written.
Expected<std::vector<std::string>> WriteRepresentationImages(
    const events::Observation& obs, const std::vector<events::EdgeSample>& esvo_samples,
    int grid_cols, int grid_rows, const std::string& dir);

}  // namespace aavio::cli
