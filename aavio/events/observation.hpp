#pragma once
/// Everything the representation stage produces at one tick (docs/architecture.md), for tracking
/// and mapping. Images are rectified unless named raw; types are explicit.

#include <opencv2/core/mat.hpp>
#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/events/adaptive_accumulation.hpp"
#include "aavio/events/edge_sampler.hpp"

namespace aavio::events {

struct RepresentationTimings {
  double time_surface_ms = 0.0;  ///< both cameras: event insertion, render, rectify, median
  double derived_ms = 0.0;       ///< negative TS and its gradients
  double aa_ms = 0.0;            ///< AA map and its rectified binary image
  double sampling_ms = 0.0;      ///< edge samples
  bool edges = false;  ///< the AA map and edge samples were built at this tick (aa/sampling_ms)
};

struct Observation {
  TimeNs t_ns = 0;
  /// Events of each camera since the previous tick (-1: not counted, an observation built
  /// elsewhere).
  std::int64_t new_events_left = -1, new_events_right = -1;
  cv::Mat ts_left, ts_right;  ///< time surfaces, rectified, median-filtered, CV_8UC1 (0–255)
  cv::Mat negative_ts_left;   ///< tracking's objective image, CV_8UC1
  cv::Mat grad_u, grad_v;     ///< Sobel/8 of negative_ts_left, CV_32FC1
  cv::Mat aa_counts_raw;      ///< AA counts in raw coordinates, CV_8UC1 (saturating)
  cv::Mat aa_map;             ///< AA map rectified, CV_8UC1: binary (255 where accumulated) or
                              ///< min(255, gain · count) (adaptive_accumulation.map_count_gain)
  std::vector<EdgeSample> samples;  ///< mapping's edge pixels (AA or ESVO's newest events)
  std::vector<AaBlock> aa_blocks;   ///< per block: closed, events, span (active lists dropped)
  std::int64_t aa_window_events = 0, aa_used_events = 0;
  RepresentationTimings timings;
};

}  // namespace aavio::events
