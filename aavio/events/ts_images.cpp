#include "aavio/events/ts_images.hpp"

#include <opencv2/imgproc.hpp>

namespace aavio::events {

void MedianFilterTs(const cv::Mat& ts, int half_size, cv::Mat* out) {
  if (half_size <= 0) {
    if (out->data != ts.data) ts.copyTo(*out);
    return;
  }
  cv::medianBlur(ts, *out, 2 * half_size + 1);
}

void SmoothTs(const cv::Mat& ts, int kernel, cv::Mat* out) {
  cv::GaussianBlur(ts, *out, cv::Size(kernel, kernel), 0.0, 0.0, cv::BORDER_REFLECT_101);
}

void NegativeTs(const cv::Mat& ts, const TimeSurfaceConfig& config, cv::Mat* out) {
  cv::Mat base;
  switch (config.negative_ts) {
    case NegativeTsMode::kGaussian:
      cv::GaussianBlur(ts, base, cv::Size(config.gaussian_kernel, config.gaussian_kernel), 0.0, 0.0,
                       cv::BORDER_REFLECT_101);
      break;
    case NegativeTsMode::kOffsetFree: {
      cv::blur(ts, base, cv::Size(config.offset_free_blur, config.offset_free_blur),
               cv::Point(-1, -1), cv::BORDER_REFLECT_101);
      ts.copyTo(base, ts > 0);  // keep the ridge where the events are; fill only empty pixels
      break;
    }
  }
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
