#include "aavio/events/ts_images.hpp"

#include <opencv2/imgproc.hpp>

namespace aavio::events {

void MedianFilterTs(const cv::Mat& ts, cv::Mat* out) {
  cv::medianBlur(ts, *out, 3);
}

void SmoothTs(const cv::Mat& ts, int kernel, cv::Mat* out) {
  cv::GaussianBlur(ts, *out, cv::Size(kernel, kernel), 0.0, 0.0, cv::BORDER_REFLECT_101);
}

void NegativeTs(const cv::Mat& ts, cv::Mat* out) {
  cv::Mat base;
  cv::GaussianBlur(ts, base, cv::Size(5, 5), 0.0, 0.0, cv::BORDER_REFLECT_101);
  cv::subtract(cv::Scalar(255), base, *out);
}

void SobelGradients(const cv::Mat& image, cv::Mat* d_u, cv::Mat* d_v) {
  if (image.type() == CV_8UC1) {
    // Both derivatives in one integer pass, then scaled: k/8 is exact in float, so the same
    // values as the float Sobel below at a third of its cost.
    cv::Mat du16, dv16;
    cv::spatialGradient(image, du16, dv16, 3, cv::BORDER_REFLECT_101);
    du16.convertTo(*d_u, CV_32F, 1.0 / 8.0);
    dv16.convertTo(*d_v, CV_32F, 1.0 / 8.0);
    return;
  }
  cv::Sobel(image, *d_u, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT_101);
  cv::Sobel(image, *d_v, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT_101);
}

}  // namespace aavio::events
