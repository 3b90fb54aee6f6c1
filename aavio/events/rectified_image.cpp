#include "aavio/events/rectified_image.hpp"

#include <cassert>
#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <opencv2/core.hpp>

namespace aavio::events {
namespace {
constexpr int kFractionBits = 7;
constexpr int kWeightBits = 2 * kFractionBits;
constexpr int kOne = 1 << kFractionBits;

std::uint8_t Interpolate1(const std::uint8_t* src, std::size_t stride, std::int32_t base,
                          const std::uint16_t* w) {
  const std::uint8_t* s = src + base;
  const std::uint32_t sum = w[0] * s[0] + w[1] * s[1] + w[2] * s[stride] + w[3] * s[stride + 1];
  return static_cast<std::uint8_t>((sum + (1u << (kWeightBits - 1))) >> kWeightBits);
}

#if defined(__SSE2__)
std::int32_t Load2(const std::uint8_t* p) {
  std::uint16_t v;
  std::memcpy(&v, p, 2);
  return v;
}
#endif

// Σ w·p over each pixel's 2×2 neighbourhood. With SSE2 four pixels at a time: their 16 source
// bytes gathered as byte pairs, widened, multiplied by the weights and pair-summed (pmaddwd);
// integer arithmetic, so exactly the scalar result.
void Interpolate(const std::uint8_t* src, std::size_t stride, const std::int32_t* base,
                 const std::uint16_t* weights, std::size_t n, std::uint8_t* dst) {
  std::size_t i = 0;
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  const __m128i half = _mm_set1_epi32(1 << (kWeightBits - 1));
  for (; i + 4 <= n; i += 4) {
    __m128i pairs = zero;
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i]), 0);
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i] + stride), 1);
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i + 1]), 2);
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i + 1] + stride), 3);
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i + 2]), 4);
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i + 2] + stride), 5);
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i + 3]), 6);
    pairs = _mm_insert_epi16(pairs, Load2(src + base[i + 3] + stride), 7);
    const __m128i w01 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(weights + 4 * i));
    const __m128i w23 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(weights + 4 * i + 8));
    const __m128i m01 = _mm_madd_epi16(_mm_unpacklo_epi8(pairs, zero), w01);
    const __m128i m23 = _mm_madd_epi16(_mm_unpackhi_epi8(pairs, zero), w23);
    const __m128 even =
        _mm_shuffle_ps(_mm_castsi128_ps(m01), _mm_castsi128_ps(m23), _MM_SHUFFLE(2, 0, 2, 0));
    const __m128 odd =
        _mm_shuffle_ps(_mm_castsi128_ps(m01), _mm_castsi128_ps(m23), _MM_SHUFFLE(3, 1, 3, 1));
    __m128i sum = _mm_add_epi32(_mm_castps_si128(even), _mm_castps_si128(odd));
    sum = _mm_srli_epi32(_mm_add_epi32(sum, half), kWeightBits);
    const __m128i bytes = _mm_packus_epi16(_mm_packs_epi32(sum, zero), zero);
    const std::int32_t packed = _mm_cvtsi128_si32(bytes);
    std::memcpy(dst + i, &packed, 4);
  }
#endif
  for (; i < n; ++i)
    dst[i] = Interpolate1(src, stride, base[i], weights + 4 * i);
}

}  // namespace

ImageRectifier::ImageRectifier(const geometry::RectificationMaps& maps)
    : width_(maps.remap_x.cols), height_(maps.remap_x.rows), valid_mask_(maps.valid_mask) {
  const int padded_width = width_ + 2;
  const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  base_.assign(n, 0);
  weights_.assign(4 * n, 0);
  for (int v = 0; v < height_; ++v) {
    for (int u = 0; u < width_; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * width_ + u;
      // Raw position, shifted by the border; rounded to 1/128 px like a fixed-point remap.
      const float x = maps.remap_x.at<float>(v, u) + 1.0f, y = maps.remap_y.at<float>(v, u) + 1.0f;
      const long xq = std::lround(static_cast<double>(x) * kOne);
      const long yq = std::lround(static_cast<double>(y) * kOne);
      const long x0 = xq >> kFractionBits, y0 = yq >> kFractionBits;
      if (!(std::isfinite(x) && std::isfinite(y)) || x0 < 0 || y0 < 0 || x0 > width_ ||
          y0 > height_) {
        continue;  // outside: weight 0 on the zero corner of the border
      }
      const int fx = static_cast<int>(xq & (kOne - 1)), fy = static_cast<int>(yq & (kOne - 1));
      base_[i] = static_cast<std::int32_t>(y0 * padded_width + x0);
      weights_[4 * i + 0] = static_cast<std::uint16_t>((kOne - fx) * (kOne - fy));
      weights_[4 * i + 1] = static_cast<std::uint16_t>(fx * (kOne - fy));
      weights_[4 * i + 2] = static_cast<std::uint16_t>((kOne - fx) * fy);
      weights_[4 * i + 3] = static_cast<std::uint16_t>(fx * fy);
    }
  }
}

cv::Mat ImageRectifier::MakePadded() const {
  return cv::Mat(height_ + 2, width_ + 2, CV_8UC1, cv::Scalar(0));
}

cv::Mat ImageRectifier::PaddedInterior(cv::Mat& padded) {
  return padded(cv::Rect(1, 1, padded.cols - 2, padded.rows - 2));
}

void ImageRectifier::Rectify(const cv::Mat& raw, cv::Mat* rectified) const {
  if (padded_.empty()) padded_ = MakePadded();
  cv::Mat interior = PaddedInterior(padded_);
  raw.copyTo(interior);
  RectifyPadded(padded_, rectified);
}

void ImageRectifier::RectifyPadded(const cv::Mat& padded, cv::Mat* rectified) const {
  assert(padded.type() == CV_8UC1 && padded.cols == width_ + 2 && padded.rows == height_ + 2 &&
         padded.isContinuous());
  rectified->create(height_, width_, CV_8UC1);
  Interpolate(padded.ptr<std::uint8_t>(), padded.step[0], base_.data(), weights_.data(),
              base_.size(), rectified->ptr<std::uint8_t>());
}

}  // namespace aavio::events
