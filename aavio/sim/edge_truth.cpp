#include "aavio/sim/edge_truth.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "aavio/events/adaptive_accumulation.hpp"
#include "aavio/geometry/rectification.hpp"
#include "aavio/sim/event_simulation.hpp"
#include "aavio/sim/renderer.hpp"

namespace aavio::sim {

cv::Mat EdgeLabels(const RenderedImage& image, const EdgeTruthConfig& config, double eta) {
  const int w = image.width, h = image.height;
  cv::Mat log_i(h, w, CV_32FC1), depth(h, w, CV_32FC1);
  for (int i = 0; i < w * h; ++i) {
    log_i.at<float>(i / w, i % w) = std::log(image.intensity[i] + 1e-3f);
    depth.at<float>(i / w, i % w) = image.depth_m[i];
  }
  cv::Mat gx, gy, dx, dy;
  cv::Sobel(log_i, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(log_i, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(depth, dx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(depth, dy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::Mat labels(h, w, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double gu = gx.at<float>(y, x), gv = gy.at<float>(y, x);
      const double du = dx.at<float>(y, x), dv = dy.at<float>(y, x);
      const double z = depth.at<float>(y, x), dz = std::hypot(du, dv);
      const bool depth_edge = z <= 0.0 ? dz > 0.0 : dz / z > config.min_depth_step;
      const bool texture_edge = std::hypot(gu, gv) > config.min_log_gradient;
      if (!depth_edge && !texture_edge) continue;
      const bool horizontal =
          texture_edge ? std::abs(gu) < eta * std::abs(gv) : std::abs(du) < eta * std::abs(dv);
      labels.at<std::uint8_t>(y, x) = horizontal ? kNearHorizontalEdge : kEdge;
    }
  }
  return labels;
}

cv::Mat EdgeTruthMask(const SimulationWorld& world, TimeNs t_ns, const EdgeTruthConfig& config) {
  const Renderer renderer(world.rig.left());
  RenderedImage image;
  renderer.Render(world.scene, world.T_world_camera(0, t_ns), t_ns, &image);
  cv::Mat edges = EdgeLabels(image, config) > 0;
  if (config.tolerance_px > 0) {
    const int k = 2 * config.tolerance_px + 1;
    cv::dilate(edges, edges, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));
  }
  return edges;
}

SampleQuality EvaluateSamples(std::span<const events::EdgeSample> samples, const cv::Mat& edges,
                              const cv::Mat& raw_valid, int grid_cols, int grid_rows) {
  SampleQuality q;
  q.samples = samples.size();
  const events::BlockGrid grid(edges.cols, edges.rows, grid_cols, grid_rows);
  std::vector<int> per_block(static_cast<std::size_t>(grid.size()), 0);
  std::vector<bool> block_has_edge(static_cast<std::size_t>(grid.size()), false);
  std::size_t on = 0;
  for (const events::EdgeSample& s : samples) {
    on += edges.at<std::uint8_t>(s.y, s.x) != 0 ? 1 : 0;
    ++per_block[grid.BlockOf(s.x, s.y)];
  }
  std::size_t usable = 0, usable_edges = 0;
  for (int y = 0; y < edges.rows; ++y) {
    for (int x = 0; x < edges.cols; ++x) {
      if (raw_valid.at<std::uint8_t>(y, x) == 0) continue;
      ++usable;
      if (edges.at<std::uint8_t>(y, x) != 0) {
        ++usable_edges;
        block_has_edge[grid.BlockOf(x, y)] = true;
      }
    }
  }
  q.on_edge = samples.empty() ? 0.0 : static_cast<double>(on) / static_cast<double>(samples.size());
  q.edge_density =
      usable == 0 ? 0.0 : static_cast<double>(usable_edges) / static_cast<double>(usable);
  q.ratio = q.edge_density > 0.0 ? q.on_edge / q.edge_density : 0.0;
  for (std::size_t b = 0; b < per_block.size(); ++b) {
    if (!samples.empty() && per_block[b] * 100 >= static_cast<int>(samples.size()))
      ++q.blocks_covered;
    if (block_has_edge[b]) ++q.blocks_with_edges;
    if (!samples.empty()) {
      q.largest_block_share =
          std::max(q.largest_block_share,
                   static_cast<double>(per_block[b]) / static_cast<double>(samples.size()));
    }
  }
  return q;
}

namespace {
void Accumulate(const SampleQuality& q, double weight, SampleQuality* mean) {
  mean->samples += q.samples;
  mean->on_edge += weight * q.on_edge;
  mean->edge_density += weight * q.edge_density;
  mean->ratio += weight * q.ratio;
  mean->blocks_covered += weight * q.blocks_covered;
  mean->blocks_with_edges += weight * q.blocks_with_edges;
  mean->largest_block_share += weight * q.largest_block_share;
}
}  // namespace

Expected<SamplingComparison> CompareEdgeSampling(const SimulationWorld& world,
                                                 std::span<const TimeNs> ticks,
                                                 const events::RepresentationConfig& config,
                                                 const EdgeTruthConfig& truth, double lead_ms) {
  const geometry::StereoRectification rectification = geometry::BuildStereoRectification(world.rig);
  StereoEventSimulation simulation(world, 1);
  SamplingComparison result;
  const double weight = ticks.empty() ? 0.0 : 1.0 / static_cast<double>(ticks.size());
  for (const TimeNs t : ticks) {
    const TimeNs start = std::max(world.spline.t_begin_ns(), t - SecondsToNs(lead_ms * 1e-3));
    simulation.Start(start);
    std::vector<events::Event> left, right;
    while (simulation.time_ns() < t)
      simulation.Step(t, &left, &right);
    events::RepresentationBuilder builder(rectification, world.rig.width(), world.rig.height(),
                                          config, start);
    AAVIO_RETURN_IF_ERROR(builder.AddEvents(events::Camera::kLeft, left));
    AAVIO_RETURN_IF_ERROR(builder.AddEvents(events::Camera::kRight, right));
    events::Observation obs;
    AAVIO_RETURN_IF_ERROR(builder.Build(t, &obs));
    const std::vector<events::EdgeSample> newest = events::SelectNewestEventsAtCount(
        left, t, rectification.left, config.edge_sampling, obs.samples.size());
    const cv::Mat edges = EdgeTruthMask(world, t, truth);
    const int cols = config.edge_sampling.grid_cols, rows = config.edge_sampling.grid_rows;
    Accumulate(EvaluateSamples(obs.samples, edges, rectification.left.raw_valid, cols, rows),
               weight, &result.aa);
    Accumulate(EvaluateSamples(newest, edges, rectification.left.raw_valid, cols, rows), weight,
               &result.esvo);
    ++result.ticks;
  }
  // The sample count as a mean too.
  for (SampleQuality* q : {&result.aa, &result.esvo}) {
    if (result.ticks == 0) break;
    q->samples /= static_cast<std::size_t>(result.ticks);
  }
  return result;
}

}  // namespace aavio::sim
