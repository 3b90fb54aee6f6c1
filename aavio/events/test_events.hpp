#pragma once
// Shared by the events tests: random event streams and identity rectification maps.

#include <algorithm>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "aavio/events/event.hpp"
#include "aavio/geometry/rectification.hpp"

namespace aavio::events::testing {

/// `n` events uniformly over a width × height sensor and [t0, t0 + duration), time-ordered.
inline std::vector<Event> RandomEvents(int n, int width, int height, TimeNs t0, TimeNs duration,
                                       std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Event> events(static_cast<std::size_t>(n));
  for (Event& e : events) {
    e.t_ns = t0 + static_cast<TimeNs>(rng() % static_cast<std::uint64_t>(duration));
    e.x = static_cast<std::uint16_t>(rng() % static_cast<std::uint64_t>(width));
    e.y = static_cast<std::uint16_t>(rng() % static_cast<std::uint64_t>(height));
    e.polarity = static_cast<std::uint8_t>(rng() % 2);
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.t_ns < b.t_ns; });
  return events;
}

/// Maps of an undistorted, unrectified camera: raw pixel = rectified pixel, all valid.
inline geometry::RectificationMaps IdentityMaps(int width, int height) {
  geometry::RectificationMaps maps;
  maps.event_lut.create(height, width, CV_32FC2);
  maps.remap_x.create(height, width, CV_32FC1);
  maps.remap_y.create(height, width, CV_32FC1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      maps.event_lut.at<cv::Vec2f>(y, x) = {static_cast<float>(x), static_cast<float>(y)};
      maps.remap_x.at<float>(y, x) = static_cast<float>(x);
      maps.remap_y.at<float>(y, x) = static_cast<float>(y);
    }
  }
  maps.valid_mask = cv::Mat(height, width, CV_8UC1, cv::Scalar(255));
  maps.raw_valid = cv::Mat(height, width, CV_8UC1, cv::Scalar(255));
  return maps;
}

}  // namespace aavio::events::testing
