#include "aavio/events/ts_images.hpp"

#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "aavio/common/vector_clones.hpp"

namespace aavio::events {
namespace {

// Sobel/8 at one pixel from its 3×3 neighbourhood: columns l, c, r of the rows above, at, below.
inline void SobelAt(const std::uint8_t* a, const std::uint8_t* m, const std::uint8_t* b, int l,
                    int c, int r, float* du, float* dv) {
  const int gu = (a[r] - a[l]) + 2 * (m[r] - m[l]) + (b[r] - b[l]);
  const int gv = (b[l] + 2 * b[c] + b[r]) - (a[l] + 2 * a[c] + a[r]);
  *du = static_cast<float>(gu) * 0.125f;
  *dv = static_cast<float>(gv) * 0.125f;
}

// One row of Sobel/8, columns reflected at both ends (OpenCV's BORDER_REFLECT_101); the interior
// in a loop the compiler vectorises (width ≥ 3).
AAVIO_AVX2_CLONES void SobelRow(const std::uint8_t* a, const std::uint8_t* m, const std::uint8_t* b,
                                int width, float* du, float* dv) {
  SobelAt(a, m, b, 1, 0, 1, du, dv);
  for (int x = 1; x < width - 1; ++x)
    SobelAt(a, m, b, x - 1, x, x + 1, du + x, dv + x);
  SobelAt(a, m, b, width - 2, width - 1, width - 2, du + width - 1, dv + width - 1);
}

}  // namespace

void MedianFilterTs(const cv::Mat& ts, cv::Mat* out) {
  cv::medianBlur(ts, *out, 3);
}

void SmoothTs(const cv::Mat& ts, int kernel, cv::Mat* out) {
  cv::GaussianBlur(ts, *out, cv::Size(kernel, kernel), 0.0, 0.0, cv::BORDER_REFLECT_101);
}

void NegativeTs(const cv::Mat& ts, cv::Mat* out) {
  // Blurred into `out` (no image allocated per tick), then 255 − value in place: for 8 bits
  // that is the bitwise complement.
  cv::GaussianBlur(ts, *out, cv::Size(5, 5), 0.0, 0.0, cv::BORDER_REFLECT_101);
  if (out->depth() == CV_8U) {
    cv::bitwise_not(*out, *out);
  } else {
    cv::subtract(cv::Scalar::all(255), *out, *out);
  }
}

void SobelGradients(const cv::Mat& image, cv::Mat* d_u, cv::Mat* d_v) {
  if (image.type() == CV_8UC1 && image.cols >= 3 && image.rows >= 2) {
    // One integer pass, each row from its neighbours (reflected at the first and last): the
    // sums are exact, and k/8 is exact in float, so the same values as the float Sobel below.
    d_u->create(image.size(), CV_32FC1);
    d_v->create(image.size(), CV_32FC1);
    const int last = image.rows - 1;
    for (int y = 0; y <= last; ++y) {
      const std::uint8_t* above = image.ptr<std::uint8_t>(y == 0 ? 1 : y - 1);
      const std::uint8_t* below = image.ptr<std::uint8_t>(y == last ? last - 1 : y + 1);
      SobelRow(above, image.ptr<std::uint8_t>(y), below, image.cols, d_u->ptr<float>(y),
               d_v->ptr<float>(y));
    }
    return;
  }
  cv::Sobel(image, *d_u, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT_101);
  cv::Sobel(image, *d_v, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT_101);
}

}  // namespace aavio::events
