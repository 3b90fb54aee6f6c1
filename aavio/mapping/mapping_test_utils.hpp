#pragma once
// Synthetic stereo images for the mapping tests: a smooth random texture and its shifted copies,
// and a textured plane as an observation.

#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "aavio/events/observation.hpp"
#include "aavio/mapping/rectified_stereo.hpp"

namespace aavio::mapping::testing {

/// A DSEC-like rectified pair geometry (f 536 px, b 0.6 m) on a small image.
inline RectifiedStereo SmallStereo(int width = 160, int height = 120) {
  return {width, height, 536.0, width / 2.0, width / 2.0, height / 2.0, 0.6};
}

/// Smooth random texture with values in 0–255 (TS-like), CV_32FC1.
inline cv::Mat Texture(int width, int height, std::uint64_t seed) {
  cv::Mat noise(height, width, CV_32FC1);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
  cv::Mat smooth;
  cv::GaussianBlur(noise, smooth, cv::Size(0, 0), 1.5);
  cv::normalize(smooth, smooth, 0.0, 255.0, cv::NORM_MINMAX);
  return smooth;
}

/// A band-limited texture of 12 random plane waves in 0–255, evaluated at (x + dx, y + dy):
/// shifts are exact (no resampling), for sub-pixel tests.
inline cv::Mat WaveTexture(int width, int height, std::uint64_t seed, double dx = 0.0,
                           double dy = 0.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), period(6.0, 20.0);
  double kx[12], ky[12], phase[12];
  for (int i = 0; i < 12; ++i) {
    const double a = angle(rng), k = 2.0 * M_PI / period(rng);
    kx[i] = k * std::cos(a), ky[i] = k * std::sin(a), phase[i] = angle(rng);
  }
  cv::Mat out(height, width, CV_32FC1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      double v = 0.0;
      for (int i = 0; i < 12; ++i)
        v += std::sin(kx[i] * (x + dx) + ky[i] * (y + dy) + phase[i]);
      out.at<float>(y, x) = static_cast<float>(127.5 + 127.5 * v / 12.0 * 2.5);
    }
  }
  return out;
}

/// `image` sampled at (x + dx, y + dy) (bilinear, border replicated).
inline cv::Mat Shifted(const cv::Mat& image, double dx, double dy) {
  cv::Mat map_x(image.size(), CV_32FC1), map_y(image.size(), CV_32FC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      map_x.at<float>(y, x) = static_cast<float>(x + dx);
      map_y.at<float>(y, x) = static_cast<float>(y + dy);
    }
  }
  cv::Mat out;
  cv::remap(image, out, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

/// A fronto-parallel textured plane at disparity 16 px (z = f·b/16 = 20.1 m) seen by the
/// SmallStereo pair, as an observation with edge samples on a grid: every map of it, from SGM and
/// from mapping cycles, must hold that depth.
inline std::shared_ptr<events::Observation> PlaneObservation() {
  auto obs = std::make_shared<events::Observation>();
  obs->t_ns = 0;
  cv::Mat left = WaveTexture(160, 120, 7), right = WaveTexture(160, 120, 7, 16.0);
  left.convertTo(obs->ts_left, CV_8U);
  right.convertTo(obs->ts_right, CV_8U);
  obs->aa_map = obs->ts_left.clone();
  cv::Sobel(left, obs->grad_u, CV_32F, 1, 0, 3, 1.0 / 8.0);
  cv::Sobel(left, obs->grad_v, CV_32F, 0, 1, 3, 1.0 / 8.0);
  for (std::uint16_t v = 12; v < 108; v += 3) {
    for (std::uint16_t u = 40; u < 150; u += 3)
      obs->samples.push_back({u, v, static_cast<float>(u), static_cast<float>(v), 2});
  }
  return obs;
}

}  // namespace aavio::mapping::testing
