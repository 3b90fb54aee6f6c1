#include "aavio/events/adaptive_accumulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aavio::events {

BlockGrid::BlockGrid(int width, int height, int cols, int rows)
    : width_(width),
      height_(height),
      cols_(cols),
      rows_(rows),
      block_col_(width),
      block_row_(height) {
  for (int x = 0; x < width; ++x)
    block_col_[x] = static_cast<int>(static_cast<std::int64_t>(x) * cols / width);
  for (int y = 0; y < height; ++y)
    block_row_[y] = static_cast<int>(static_cast<std::int64_t>(y) * rows / height);
}

double NonZeroVariance(const cv::Mat& counts, const cv::Rect& region) {
  double s1 = 0.0, s2 = 0.0, n = 0.0;
  for (int y = region.y; y < region.y + region.height; ++y) {
    for (int x = region.x; x < region.x + region.width; ++x) {
      const double a = counts.at<std::uint16_t>(y, x);
      if (a <= 0.0) continue;
      s1 += a, s2 += a * a, n += 1.0;
    }
  }
  if (n == 0.0) return 0.0;
  const double mean = s1 / n;
  return s2 / n - mean * mean;
}

AdaptiveAccumulator::AdaptiveAccumulator(int width, int height,
                                         const AdaptiveAccumulationConfig& config)
    : config_(config),
      grid_(width, height, config.grid_cols, config.grid_rows),
      counts_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0) {}

void AdaptiveAccumulator::Accumulate(const Event& e, AaMap* out) {
  const std::size_t pixel = static_cast<std::size_t>(e.y) * grid_.width() + e.x;
  const int b = grid_.BlockOf(e.x, e.y);
  AaBlock& block = out->blocks[b];
  const std::uint16_t c = counts_[pixel];
  if (c == 0) {
    touched_.push_back(static_cast<std::uint32_t>(pixel));
    block.active.push_back(static_cast<std::uint32_t>(pixel));
  }
  if (c == 0xffff) return;
  counts_[pixel] = static_cast<std::uint16_t>(c + 1);
  s1_[b] += 1.0;
  s2_[b] += 2.0 * c + 1.0;  // (c + 1)² − c²
  ++block.events;
  first_ns_[b] = std::min(first_ns_[b], e.t_ns);
  last_ns_[b] = std::max(last_ns_[b], e.t_ns);
  ++out->used_events;
}

void AdaptiveAccumulator::Build(std::span<const Event> events, TimeNs t_ns, AaMap* out) {
  for (const std::uint32_t pixel : touched_)
    counts_[pixel] = 0;
  touched_.clear();
  const int nb = grid_.size();
  out->t_ns = t_ns;
  out->blocks.resize(static_cast<std::size_t>(nb));
  for (AaBlock& block : out->blocks) {
    block.active.clear();
    block.events = 0;
    block.closed = false;
    block.span_ns = 0;
    block.contrast = 0.0;
  }
  s1_.assign(nb, 0.0);
  s2_.assign(nb, 0.0);
  first_ns_.assign(nb, std::numeric_limits<TimeNs>::max());
  last_ns_.assign(nb, std::numeric_limits<TimeNs>::min());
  out->used_events = 0;

  // The window (t − window, t] of the time-ordered events.
  const TimeNs window_ns = SecondsToNs(config_.window_ms * 1e-3);
  auto by_time = [](const Event& e, TimeNs t) { return e.t_ns <= t; };
  const auto begin = std::lower_bound(events.begin(), events.end(), t_ns - window_ns, by_time);
  const auto end = std::lower_bound(begin, events.end(), t_ns, by_time);
  const std::span<const Event> window(begin, end);
  out->window_events = static_cast<std::int64_t>(window.size());

  BuildContrast(window, t_ns, out);

  for (int b = 0; b < nb; ++b) {
    AaBlock& block = out->blocks[b];
    if (block.events > 0) block.span_ns = last_ns_[b] - first_ns_[b];
    if (!block.closed && !block.active.empty()) {
      const double n = static_cast<double>(block.active.size());
      block.contrast = s2_[b] / n - (s1_[b] / n) * (s1_[b] / n);
    }
  }
  out->counts.create(grid_.height(), grid_.width(), CV_8UC1);
  out->counts.setTo(0);
  std::uint8_t* counts = out->counts.ptr<std::uint8_t>();
  for (const std::uint32_t pixel : touched_)
    counts[pixel] = static_cast<std::uint8_t>(std::min<std::uint16_t>(counts_[pixel], 255));
}

void AdaptiveAccumulator::BuildContrast(std::span<const Event> window, TimeNs t_ns, AaMap* out) {
  const TimeNs dt_ns = std::max<TimeNs>(1, SecondsToNs(config_.check_interval_ms * 1e-3));
  auto check = [&] {
    for (std::size_t b = 0; b < out->blocks.size(); ++b) {
      AaBlock& block = out->blocks[b];
      if (block.closed || block.active.empty()) continue;
      const double n = static_cast<double>(block.active.size());
      const double contrast = s2_[b] / n - (s1_[b] / n) * (s1_[b] / n);
      if (contrast > config_.contrast_threshold) {
        block.closed = true;
        block.contrast = contrast;
      }
    }
  };
  auto open = [&](const Event& e) { return !out->blocks[grid_.BlockOf(e.x, e.y)].closed; };
  // Newest first, checks on a fixed grid of event time: every δt back from the tick.
  TimeNs next_check = t_ns - dt_ns;
  for (auto it = window.rbegin(); it != window.rend(); ++it) {
    while (it->t_ns <= next_check) {
      check();
      next_check -= dt_ns;
    }
    if (open(*it)) Accumulate(*it, out);
  }
}

}  // namespace aavio::events
