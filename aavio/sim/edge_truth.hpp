#pragma once
/// Ground truth for edge pixels: where, at a given time, the raw left image of a simulation has
/// an edge — a step of log intensity (texture edges, silhouettes) or of depth (occlusion
/// boundaries). Used to check that the edge samples mapping receives lie on real structure
/// (issue: "sampled pixels lie on true edges far more often than random pixels").

#include <opencv2/core/mat.hpp>
#include <span>

#include "aavio/events/edge_sampler.hpp"
#include "aavio/events/representation_builder.hpp"
#include "aavio/sim/renderer.hpp"
#include "aavio/sim/world.hpp"

namespace aavio::sim {

struct EdgeTruthConfig {
  double min_log_gradient = 0.25;  ///< |∇ log I| per pixel (Sobel/8): one event threshold per pixel
  double min_depth_step = 0.05;    ///< relative depth change per pixel that makes an edge
  int tolerance_px = 1;            ///< edges are dilated by this much (events blur ±1 px)
};

/// Edge labels of a rendered image (no dilation): 0 none, kEdge, or kNearHorizontalEdge where the
/// edge's gradient is nearly vertical (|g_u| < eta·|g_v|: the edge runs along the baseline, the
/// case temporal stereo is for). Depth edges use the depth gradient's direction.
constexpr std::uint8_t kEdge = 128, kNearHorizontalEdge = 255;
cv::Mat EdgeLabels(const RenderedImage& image, const EdgeTruthConfig& config, double eta = 0.2);

/// CV_8UC1 over the raw left image at t_ns: 255 on edges (dilated), 0 elsewhere.
cv::Mat EdgeTruthMask(const SimulationWorld& world, TimeNs t_ns, const EdgeTruthConfig& config);

struct SampleQuality {
  std::size_t samples = 0;
  double on_edge = 0.0;              ///< share of samples on a true edge
  double edge_density = 0.0;         ///< share of usable pixels (raw_valid) on a true edge
  double ratio = 0.0;                ///< on_edge / edge_density: how much better than random
  double blocks_covered = 0;         ///< grid blocks holding at least 1 % of the samples
  double blocks_with_edges = 0;      ///< grid blocks with any true edge pixel
  double largest_block_share = 0.0;  ///< share of the samples in the fullest block
};

SampleQuality EvaluateSamples(std::span<const events::EdgeSample> samples, const cv::Mat& edges,
                              const cv::Mat& raw_valid, int grid_cols, int grid_rows);

/// AA sampling against ESVO's newest events at the same point count, averaged over ticks. At each
/// tick the simulation runs the `lead_ms` before it in memory, an Observation is built, ESVO's
/// selection takes as many events as AA gave samples, and both are scored against the truth.
struct SamplingComparison {
  SampleQuality aa, esvo;  ///< means over the ticks
  int ticks = 0;
};
Expected<SamplingComparison> CompareEdgeSampling(const SimulationWorld& world,
                                                 std::span<const TimeNs> ticks,
                                                 const events::RepresentationConfig& config,
                                                 const EdgeTruthConfig& truth,
                                                 double lead_ms = 30.0);

}  // namespace aavio::sim
