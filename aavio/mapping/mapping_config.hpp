#pragma once
/// Configuration of mapping (docs/mapping.md). Defaults are the paper's / ICRA code's
/// DSEC values; configs/indoor.yaml and configs/driving.yaml are the scene presets, and
/// config/sensor_rules.hpp derives the camera-dependent ones.

#include <array>
#include <cstddef>
#include <string>
#include <utility>

#include "aavio/common/config_fields.hpp"

namespace aavio::mapping {

/// The inverse depths mapping keeps, [min, max] in 1/m (MappingConfig's inv_depth_min/max).
struct InvDepthRange {
  double min = 0.0, max = 0.0;
  bool Contains(double rho) const { return rho >= min && rho <= max; }
};

/// Left/right block matching along rectified rows (docs/mapping.md), over the disparities
/// the depth range [1/inv_depth_max, 1/inv_depth_min] allows.
struct StaticStereoConfig {
  double zncc_threshold = 0.1;      ///< θ: accept cost ½(1 − ZNCC) below it ([ICRA], [ESVO])
  bool smooth_time_surface = true;  ///< Gaussian 5×5 on the TS before matching (DSEC configs)
  /// Reject a match when another local minimum's ZNCC is within this fraction of the best's
  /// (e.g. 0.1: a rival with ≥ 90 % of the best correlation); 0 = off, as the reference codes.
  double uniqueness = 0.0;
  /// aavio: match the right patch back along the left row; reject unless it lands within this
  /// many pixels of the left point (a left-right consistency check); < 0 = off, as the reference.
  int left_right_tolerance_px = -1;
  /// aavio (0 = off): drop a match when the previous map holds, within this many pixels, a
  /// surface so near that the pixel's true match lies outside the right image, and the match is
  /// over 20 % farther than that surface (out_of_view_check.hpp). Near the left border the
  /// search cannot reach the true disparity and settles on another edge.
  int out_of_view_radius_px = 0;

  template <typename V>
  void VisitFields(V&& v) {
    v("zncc_threshold", zncc_threshold,
      "θ: accept a static match whose cost ½(1 − ZNCC) is below it");
    v("smooth_time_surface", smooth_time_surface,
      "Gaussian 5×5 on the time surfaces before static matching");
    v("uniqueness", uniqueness,
      "reject a match with a rival minimum within this fraction of its correlation (aavio)");
    v("left_right_tolerance_px", left_right_tolerance_px,
      "left-right check: the back match must land this close; < 0 off (aavio)");
    v("out_of_view_radius_px", out_of_view_radius_px,
      "drop left-border matches the previous map says are out of view; 0 off (aavio)");
  }
  Status Validate() const;
};

/// AA-now vs AA-past matching for edges parallel to the baseline (docs/mapping.md); the fixed
/// parts are in temporal_stereo.hpp.
struct TemporalStereoConfig {
  bool enabled = true;
  double min_translation_m = 0.3;  ///< partner at least this far away ([ICRA] 0.3 hard-coded)
  /// Skip pixels whose epipolar segment over the depth range is shorter than this (aavio; 0 =
  /// off): under forward motion pixels near the focus of expansion have almost no parallax.
  double min_parallax_px = 0.0;
  /// Reject a match whose depth would move by more than this fraction for one pixel of matching
  /// error (aavio; 0 = off): triangulation too ill-conditioned to be worth a map point. A short
  /// baseline (a hand-held camera's few centimetres) fails it nearly always.
  double max_relative_depth_error = 0.0;
  /// Gaussian 5×5 on the AA maps before matching (aavio): sub-pixel matching and refinement
  /// gradients on wide event bands; on DAVIS-sized images it costs near-horizontal completeness.
  bool smooth_aa = false;
  /// Cross-check against a second partner (aavio; 0 = off): the newest observation at least
  /// 1.5 × min_translation_m beyond the first partner is searched too, and a match is kept only
  /// if both depths agree within this many pixels of matching error (the sum of both searches'
  /// depth change per pixel); the depth is then their precision-weighted mean. A wrong match on
  /// a repeated or ambiguous structure rarely lands on the same depth in two views.
  double cross_check_px = 0.0;
  /// Culling of temporal estimates, whose residual is on the AA maps, not the time surfaces
  /// ([ESVO2] residual_vis_threshold_ln, stdVar_vis_threshold_ln); ≤ 0: depth_refinement's.
  double residual_threshold = 0.0;
  double max_inv_depth_stddev = 0.0;
  double min_depth_m = 0.8;  ///< triangulated depth gate ([ICRA] 0.8–40 m hard-coded)
  double max_depth_m = 40.0;

  template <typename V>
  void VisitFields(V&& v) {
    v("enabled", enabled,
      "temporal stereo for near-horizontal edges (paper); off: static stereo only");
    v("min_translation_m", min_translation_m,
      "the temporal partner is at least this far from the current pose [m]");
    v("min_parallax_px", min_parallax_px,
      "skip pixels with less parallax over the depth range; 0 off (aavio) [px]");
    v("max_relative_depth_error", max_relative_depth_error,
      "drop matches 1 px of error would move by more than this fraction (aavio)");
    v("smooth_aa", smooth_aa, "Gaussian 5×5 on the AA maps before temporal matching (aavio)");
    v("cross_check_px", cross_check_px,
      "a second, older partner must agree within this many pixels; 0 off (aavio)");
    v("residual_threshold", residual_threshold,
      "cull temporal estimates by their AA residual; 0: refinement's threshold");
    v("max_inv_depth_stddev", max_inv_depth_stddev,
      "cull temporal estimates by σ_ρ [1/m]; 0: refinement's threshold");
    v("min_depth_m", min_depth_m, "nearest depth temporal stereo may triangulate [m]");
    v("max_depth_m", max_depth_m, "farthest depth temporal stereo may triangulate [m]");
  }
  Status Validate() const;
};

/// Per-point Student-t refinement and culling (docs/mapping.md).
struct DepthRefinementConfig {
  double student_t_nu = 2.182;        ///< ν of the TS residual ([ESVO2], DSEC all versions)
  double student_t_scale = 17.277;    ///< s of the TS residual [TS levels]
  double residual_threshold = 30.0;   ///< cull if cost > threshold² × patch area [TS levels]
  double max_inv_depth_stddev = 1.0;  ///< cull if σ_ρ above it [1/m] (DSEC 1 = effectively off)
  /// Cull if σ_ρ / ρ (≈ relative depth uncertainty) is above it (aavio; 0 = off): far points
  /// with a pixel or two of disparity carry depth errors of tens of percent.
  double max_relative_stddev = 0.0;

  template <typename V>
  void VisitFields(V&& v) {
    v("student_t_nu", student_t_nu, "ν of the Student-t residual model");
    v("student_t_scale", student_t_scale,
      "scale s of the Student-t residual model [time-surface levels]");
    v("residual_threshold", residual_threshold,
      "cull an estimate whose cost exceeds threshold² × patch area");
    v("max_inv_depth_stddev", max_inv_depth_stddev,
      "cull an estimate (and a fused point) with σ_ρ above it [1/m]");
    v("max_relative_stddev", max_relative_stddev,
      "cull an estimate with σ_ρ / ρ above it; 0 off (aavio)");
  }
  Status Validate() const;
};

enum class FusionStrategy {
  kConstFrames,  ///< keep the newest max_frames batches
  kConstPoints,  ///< drop the oldest batches while points > 1.5 × max_points
};

/// Student-t fusion into the depth grid of the current pose (docs/mapping.md).
struct FusionConfig {
  FusionStrategy strategy = FusionStrategy::kConstFrames;
  int max_frames = 5;      ///< FIFO length in batches ([ESVO] DSEC 5)
  int max_points = 20000;  ///< FIFO size for const_points
  int radius = 1;          ///< 0: 2×2 cells, ≥ 1: 3×3 cells
  /// Maps are published as the reference codes do (docs/mapping.md): the bootstrap map, then
  /// (const_frames) only maps of a full FIFO, which are cleaned, or (const_points) maps of a FIFO
  /// more than half full. True (aavio) also gives tracking the maps fused while the FIFO fills
  /// (every unconfirmed estimate, spread over its cells). Depth outputs and evaluation take only
  /// cleaned maps either way (LocalMap::confirmed).
  bool publish_while_filling = false;
  /// A point's age counts only fusions with estimates of other batches (another observation,
  /// or the other kind of stereo): a neighbouring sample of its own batch, spread into a shared
  /// cell, is no confirmation (aavio; the reference codes count every fusion).
  bool confirm_across_batches = false;
  /// A const_points FIFO also counts as full (cleaned, confirmed, published) once it holds
  /// max_frames batches: a sparse scene's few dozen points a cycle may never reach max_points,
  /// and then no map would ever be cleaned or written (aavio; the reference codes count points).
  bool full_at_max_frames = true;

  template <typename V>
  void VisitFields(V&& v) {
    v("strategy", strategy,
      "the fusion FIFO: the newest max_frames batches, or up to max_points points");
    v("max_frames", max_frames, "batches a const_frames FIFO holds");
    v("max_points", max_points, "points a const_points FIFO holds");
    v("radius", radius, "cells each estimate is fused into: 0 → 2×2, 1 → 3×3");
    v("publish_while_filling", publish_while_filling,
      "tracking also gets the maps of a filling FIFO (aavio)");
    v("confirm_across_batches", confirm_across_batches,
      "only an estimate of another batch confirms a point (aavio)");
    v("full_at_max_frames", full_at_max_frames,
      "a const_points FIFO is also full at max_frames batches: sparse scenes (aavio)");
  }
  Status Validate() const;
};

/// Optional neighbourhood regularisation of the depth grid (docs/mapping.md).
/// [ESVO] rpg: a point is kept when at least 8 of the points within 5 px (and 8 of those within
/// its 2σ reach) exist.
struct RegularizationConfig {
  bool enabled = false;  ///< [ICRA] DSEC off; [ESVO], [ESVO2] rpg on

  template <typename V>
  void VisitFields(V&& v) {
    v("enabled", enabled, "neighbourhood regularisation of each cleaned map (ESVO rpg)");
  }
  Status Validate() const { return Status::Ok(); }
};

enum class BootstrapMethod {
  kSgm,            ///< OpenCV StereoSGBM on the time-surface pair (the reference codes)
  kBlockMatching,  ///< the mapping cycle's static stereo (aavio)
};

/// The bootstrap of the first map (docs/mapping.md).
struct BootstrapConfig {
  /// Accept the initial map with at least this many points ([ESVO], [ICRA]) — or, in a scene with
  /// fewer edges, with a depth at min_coverage of the edge samples static stereo can match (not
  /// along a near-horizontal edge, by mapping.eta) and at least kMinRegistrationPoints: what the
  /// scene offers, not a count a dense scene sets.
  int min_points = 500;
  /// aavio (0: min_points alone, as the references): the share of the edge samples static stereo
  /// can match that must get a depth for a map of fewer than min_points points.
  double min_coverage = 0.5;
  static constexpr std::size_t kMinRegistrationPoints = 50;
  /// sgm: the reference codes (StereoSGBM, block 11, σ_ρ 0.001 /m). block_matching (aavio): the
  /// cycle's own static stereo on every edge sample (ZNCC block matching with its checks,
  /// refinement and culling).
  BootstrapMethod method = BootstrapMethod::kSgm;

  template <typename V>
  void VisitFields(V&& v) {
    v("min_points", min_points, "points that make a first map whatever the scene");
    v("min_coverage", min_coverage,
      "or fewer (50 at least) with a depth at this share of the samples stereo can match (aavio)");
    v("method", method, "the first map: sgm (reference) or the cycle's block matching (aavio)");
  }
  Status Validate() const;
  /// Whether `points` depths found among `matchable` edge samples (those static stereo can
  /// match) make a first map.
  bool Accepts(std::size_t points, std::size_t matchable) const {
    return points >= static_cast<std::size_t>(min_points) ||
           (min_coverage > 0.0 && points >= kMinRegistrationPoints &&
            static_cast<double>(points) >= min_coverage * static_cast<double>(matchable));
  }
  /// Why `points` are not enough, for the bootstrap's failure message: `matchable` of the
  /// `samples` edge samples are not along a near-horizontal edge.
  std::string Refusal(const char* stereo, std::size_t points, std::size_t matchable,
                      std::size_t samples) const;
};

struct MappingConfig {
  double rate_hz = 20.0;         ///< mapping cycles per second of data time ([ICRA], [ESVO])
  double inv_depth_min = 0.001;  ///< 1/m: farthest depth 1000 m (DSEC configs)
  double inv_depth_max = 0.25;   ///< 1/m: nearest depth 4 m (DSEC configs)
  int max_points = 2500;         ///< edge pixels per cycle ([ICRA] DSEC PROCESS_EVENT_NUM)
  double eta = 0.2;              ///< |g_u|/|g_v| below it → temporal stereo [paper]
  /// aavio: move each edge sample up to this far [px] along the time-surface gradient onto the
  /// newest edge (the negative TS's valley) before matching (edge_snapping.hpp); 0 = off, as the
  /// paper and the reference codes. Removes a scale drift of 2–10 % on the DSEC twins.
  double snap_to_edge_px = 2.0;
  /// aavio: static and temporal stereo search only the depths the previous map predicts near
  /// each sample (its points' 3σ; disparity_prediction.hpp), the whole range where it predicts
  /// nothing or the best lies at a cut end of the window; false = always the whole range, as the
  /// paper and the reference codes.
  bool predicted_search = true;
  StaticStereoConfig static_stereo;
  TemporalStereoConfig temporal_stereo;
  DepthRefinementConfig depth_refinement;
  FusionConfig fusion;
  RegularizationConfig regularization;
  BootstrapConfig bootstrap;

  InvDepthRange inv_depth_range() const { return {inv_depth_min, inv_depth_max}; }

  template <typename V>
  void VisitFields(V&& v) {
    v("rate_hz", rate_hz, "mapping cycles per second of data time");
    v("inv_depth_min", inv_depth_min, "inverse of the farthest depth mapped [1/m]");
    v("inv_depth_max", inv_depth_max, "inverse of the nearest depth mapped [1/m]");
    v("max_points", max_points, "edge samples a mapping cycle uses at most");
    v("eta", eta, "η: |g_u| / |g_v| below it sends a sample to temporal stereo");
    v("snap_to_edge_px", snap_to_edge_px,
      "move samples up to this far onto the newest edge; 0 off (aavio) [px]");
    v("predicted_search", predicted_search,
      "stereo searches only the depths the previous map predicts, where it has any (aavio)");
    v("static_stereo", static_stereo);
    v("temporal_stereo", temporal_stereo);
    v("depth_refinement", depth_refinement);
    v("fusion", fusion);
    v("regularization", regularization);
    v("bootstrap", bootstrap);
  }
  Status Validate() const;
};

}  // namespace aavio::mapping

namespace aavio {
template <>
struct EnumNames<mapping::FusionStrategy> {
  static constexpr std::array kNames = {
      std::pair{mapping::FusionStrategy::kConstFrames, "const_frames"},
      std::pair{mapping::FusionStrategy::kConstPoints, "const_points"}};
};
template <>
struct EnumNames<mapping::BootstrapMethod> {
  static constexpr std::array kNames = {
      std::pair{mapping::BootstrapMethod::kSgm, "sgm"},
      std::pair{mapping::BootstrapMethod::kBlockMatching, "block_matching"}};
};
}  // namespace aavio
