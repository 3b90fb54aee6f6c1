#pragma once
/// Configuration of the event representations (algorithm.md §2–3, §10.1). Defaults are the
/// paper's / ICRA code's values; the provenance of each is given beside it.

#include <array>
#include <utility>

#include "aavio/common/config_fields.hpp"

namespace aavio::events {

/// How the tracking objective's negative time surface is made (algorithm.md §2.3).
enum class NegativeTsMode {
  kGaussian,    ///< 255 − Gaussian(TS) ([ESVO], [ICRA code])
  kOffsetFree,  ///< 255 − OS-TS: TS where > 0, box-blurred TS elsewhere ([ESVO2 code])
};

struct TimeSurfaceConfig {
  double rate_hz = 100.0;    ///< TS/AA generation rate in data time, one "tick" each [paper]
  double decay_ms = 30.0;    ///< exponential decay τ [ms] ([ICRA], [ESVO]; ESVO2 uses 20)
  int median_half_size = 1;  ///< median filter kernel 2k+1 after rectification (1 → 3×3)
  NegativeTsMode negative_ts = NegativeTsMode::kGaussian;  ///< tracking objective image
  int gaussian_kernel = 5;   ///< Gaussian kernel size for the negative TS ([ESVO] kernelSize)
  int offset_free_blur = 7;  ///< box filter size for the offset-free TS ([ESVO2] blur_size)
  /// Keep one of every n/k+1 events of a 1 ms packet with n > k events (ICRA safety valve);
  /// 0 disables.
  int max_events_per_ms = 0;

  template <typename V>
  void VisitFields(V&& v) {
    v("rate_hz", rate_hz);
    v("decay_ms", decay_ms);
    v("median_half_size", median_half_size);
    v("negative_ts", negative_ts);
    v("gaussian_kernel", gaussian_kernel);
    v("offset_free_blur", offset_free_blur);
    v("max_events_per_ms", max_events_per_ms);
  }
  Status Validate() const;
};

/// The rule that closes a block of the adaptive accumulation map (algorithm.md §3.2–3.3).
enum class AaStopRule {
  kContrast,  ///< variance of the non-zero counts > β, checked every δt [paper Alg. 1]
  kActivity,  ///< event-activity convergence ([ESVO2 code])
};
enum class AaOrder {
  kNewestFirst,  ///< accumulate backwards from the tick (recommended, [ESVO2])
  kForward,      ///< accumulate from the window start ([ICRA code])
};

struct AdaptiveAccumulationConfig {
  AaStopRule stop_rule = AaStopRule::kContrast;
  AaOrder order = AaOrder::kNewestFirst;
  int grid_cols = 8;  ///< blocks across; w = width / grid_cols (80 px at 640, 30 px at 240) [paper]
  int grid_rows = 6;  ///< blocks down
  double check_interval_ms = 2.0;    ///< δt between contrast checks [paper] (ICRA code: 1)
  double contrast_threshold = 0.5;   ///< β [paper]
  double window_ms = 10.0;           ///< events considered per AA map (one tick)
  double activity_tolerance = 0.95;  ///< [ESVO2] stop when |A_rev − A_fin| < tolerance
  int activity_check_events = 10;    ///< [ESVO2] events per block between checks
  /// The rectified AA map temporal stereo matches: 0 = binary, 255 where at least one event was
  /// accumulated ([ICRA code]); g > 0 (aavio): min(255, g · count), so that the pixels an edge
  /// crossed with more events weigh more, and an edge's band reads as a ridge rather than a
  /// plateau whose width follows the motion.
  int map_count_gain = 0;

  template <typename V>
  void VisitFields(V&& v) {
    v("stop_rule", stop_rule);
    v("order", order);
    v("grid_cols", grid_cols);
    v("grid_rows", grid_rows);
    v("check_interval_ms", check_interval_ms);
    v("contrast_threshold", contrast_threshold);
    v("window_ms", window_ms);
    v("activity_tolerance", activity_tolerance);
    v("activity_check_events", activity_check_events);
    v("map_count_gain", map_count_gain);
  }
  Status Validate() const;
};

/// Where mapping's edge pixels come from (algorithm.md §3.4–3.5).
enum class SamplingMode {
  kAdaptiveAccumulation,  ///< sample the AA map [paper]
  kNewestEvents,          ///< ESVO: the newest events of the last window (baseline)
};

struct EdgeSamplingConfig {
  SamplingMode mode = SamplingMode::kAdaptiveAccumulation;
  int num_points = 2500;  ///< budget M ([ICRA code] DSEC 2500, the paper's "~2.5k")
  int grid_cols = 8;      ///< sampling blocks across ([ICRA] 80 px blocks at 640×480)
  int grid_rows = 6;
  double proportional_share =
      0.75;  ///< share of M given out in proportion to active pixels [ESVO2]
  double block_cap_fraction =
      0.5;  ///< a block gives at most this share of its active pixels [ESVO2]
  /// AA mode (aavio; 0 = the paper, the reference codes): no two samples within this many
  /// pixels (Chebyshev) while a block has candidates that keep the spacing; its quota is then
  /// filled with the rest in the same order. Highest counts cluster on a few strong edges and
  /// their trails, where neighbouring samples repeat one patch match; spread out, the same
  /// budget covers more edges (docs/mapping.md).
  int min_spacing_px = 0;
  double newest_window_ms = 10.0;  ///< ESVO mode: events of the last window [ESVO]
  bool denoise = false;            ///< ESVO mode: 3×3 median mask on the event image [ESVO rpg]

  template <typename V>
  void VisitFields(V&& v) {
    v("mode", mode);
    v("num_points", num_points);
    v("grid_cols", grid_cols);
    v("grid_rows", grid_rows);
    v("proportional_share", proportional_share);
    v("block_cap_fraction", block_cap_fraction);
    v("min_spacing_px", min_spacing_px);
    v("newest_window_ms", newest_window_ms);
    v("denoise", denoise);
  }
  Status Validate() const;
};

}  // namespace aavio::events

namespace aavio {
template <>
struct EnumNames<events::NegativeTsMode> {
  static constexpr std::array kNames = {
      std::pair{events::NegativeTsMode::kGaussian, "gaussian"},
      std::pair{events::NegativeTsMode::kOffsetFree, "offset_free"}};
};
template <>
struct EnumNames<events::AaStopRule> {
  static constexpr std::array kNames = {std::pair{events::AaStopRule::kContrast, "contrast"},
                                        std::pair{events::AaStopRule::kActivity, "activity"}};
};
template <>
struct EnumNames<events::AaOrder> {
  static constexpr std::array kNames = {std::pair{events::AaOrder::kNewestFirst, "newest_first"},
                                        std::pair{events::AaOrder::kForward, "forward"}};
};
template <>
struct EnumNames<events::SamplingMode> {
  static constexpr std::array kNames = {
      std::pair{events::SamplingMode::kAdaptiveAccumulation, "adaptive_accumulation"},
      std::pair{events::SamplingMode::kNewestEvents, "newest_events"}};
};
}  // namespace aavio
