#pragma once
/// Configuration of the event representations (docs/representations.md). Defaults are the
/// paper's / ICRA code's values; the provenance of each is given beside it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "aavio/common/config_fields.hpp"

namespace aavio::events {

struct TimeSurfaceConfig {
  double rate_hz = 100.0;  ///< TS/AA generation rate in data time, one "tick" each [paper]
  double decay_ms = 30.0;  ///< exponential decay τ [ms] ([ICRA], [ESVO]; ESVO2 uses 20)
  /// aavio (off: a fixed τ, as the references): τ is kept at least as long as the events at the
  /// map's edges are old (their median age over the last ticks, up to 10 τ), so that a slow camera
  /// or a sparse scene still draws its edges (tracking/edge_age.hpp).
  bool adaptive_decay = true;

  template <typename V>
  void VisitFields(V&& v) {
    v("rate_hz", rate_hz,
      "ticks per second of data time: one time surface and one registration each");
    v("decay_ms", decay_ms, "exponential decay τ of the time surface [ms]");
    v("adaptive_decay", adaptive_decay,
      "τ at least the age of the events at the map's edges, up to 10x (aavio)");
  }
  Status Validate() const;
};

struct AdaptiveAccumulationConfig {
  int grid_cols = 8;  ///< blocks across; w = width / grid_cols (80 px at 640, 30 px at 240) [paper]
  int grid_rows = 6;  ///< blocks down
  double check_interval_ms = 2.0;   ///< δt between contrast checks [paper] (ICRA code: 1)
  double contrast_threshold = 0.5;  ///< β [paper]
  double window_ms = 10.0;          ///< events considered per AA map (one tick)
  /// The rectified AA map temporal stereo matches: 0 = binary, 255 where at least one event was
  /// accumulated ([ICRA code]); g > 0 (aavio): min(255, g · count), so that the pixels an edge
  /// crossed with more events weigh more, and an edge's band reads as a ridge rather than a
  /// plateau whose width follows the motion.
  int map_count_gain = 0;

  template <typename V>
  void VisitFields(V&& v) {
    v("grid_cols", grid_cols, "blocks across the image");
    v("grid_rows", grid_rows, "blocks down the image");
    v("check_interval_ms", check_interval_ms,
      "δt: event time between a block's contrast checks [ms]");
    v("contrast_threshold", contrast_threshold,
      "β: a block freezes once the variance of its non-zero counts exceeds it");
    v("window_ms", window_ms, "events a map may accumulate, back from the tick [ms]");
    v("map_count_gain", map_count_gain,
      "AA map for temporal stereo: 0 binary, g > 0 min(255, g · count) (aavio)");
  }
  Status Validate() const;
};

/// Where mapping's edge pixels come from (docs/representations.md).
enum class SamplingMode {
  kAdaptiveAccumulation,  ///< sample the AA map [paper]
  kNewestEvents,          ///< ESVO: the newest events of the last window (baseline)
};

struct EdgeSamplingConfig {
  SamplingMode mode = SamplingMode::kAdaptiveAccumulation;
  int num_points = 2500;  ///< budget M ([ICRA code] DSEC 2500, the paper's "~2.5k")
  int grid_cols = 8;      ///< sampling blocks across ([ICRA] 80 px blocks at 640×480)
  int grid_rows = 6;
  /// AA mode (aavio; 0 = the paper, the reference codes): no two samples within this many
  /// pixels (Chebyshev) while a block has candidates that keep the spacing; its quota is then
  /// filled with the rest in the same order. Highest counts cluster on a few strong edges and
  /// their trails, where neighbouring samples repeat one patch match; spread out, the same
  /// budget covers more edges (docs/mapping.md).
  int min_spacing_px = 0;

  template <typename V>
  void VisitFields(V&& v) {
    v("mode", mode,
      "where mapping's samples come from: the AA map (paper) or ESVO's newest events");
    v("num_points", num_points, "samples per tick (the budget M)");
    v("grid_cols", grid_cols, "sampling blocks across the image");
    v("grid_rows", grid_rows, "sampling blocks down the image");
    v("min_spacing_px", min_spacing_px,
      "no two AA samples within this many pixels while a block has others (aavio)");
  }
  Status Validate() const;
};

/// What the representation stage needs (RepresentationBuilder): its three sections, the seed of
/// its random choices and its memory bound.
struct RepresentationConfig {
  TimeSurfaceConfig time_surface;
  AdaptiveAccumulationConfig adaptive_accumulation;
  EdgeSamplingConfig edge_sampling;
  std::uint64_t seed = 1;
  /// Per camera: events waiting for the next tick, and events kept for the AA window, beyond
  /// this many are dropped, oldest first (a burst: a flash, a broken driver). Bounds memory.
  std::size_t max_buffered_events = 5'000'000;
};

}  // namespace aavio::events

namespace aavio {
template <>
struct EnumNames<events::SamplingMode> {
  static constexpr std::array kNames = {
      std::pair{events::SamplingMode::kAdaptiveAccumulation, "adaptive_accumulation"},
      std::pair{events::SamplingMode::kNewestEvents, "newest_events"}};
};
}  // namespace aavio
