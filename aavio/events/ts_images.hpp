#pragma once
/// The images derived from a rectified time surface (docs/representations.md): the smoothed TS used
/// by static stereo, the negative TS that tracking registers against (ESVO's Gaussian form) and its
/// Sobel gradients. All CV_8UC1 in, explicit types out.

#include <opencv2/core/mat.hpp>

namespace aavio::events {

/// TS after its 3×3 median filter ([ESVO], [ICRA code]). In place allowed.
void MedianFilterTs(const cv::Mat& ts, cv::Mat* out);

/// Gaussian 5×5 (σ from the size, as OpenCV) smoothed TS for static stereo.
void SmoothTs(const cv::Mat& ts, int kernel, cv::Mat* out);

/// 255 − G(TS), G a 5×5 Gaussian ([ESVO] kernelSize, [ICRA code]).
void NegativeTs(const cv::Mat& ts, cv::Mat* out);

/// 3×3 Sobel derivatives ∂u, ∂v of an image, divided by 8 (so they are per-pixel slopes), CV_32F;
/// reflected at the image's borders (a view's surroundings are not read).
void SobelGradients(const cv::Mat& image, cv::Mat* d_u, cv::Mat* d_v);

}  // namespace aavio::events
