#pragma once
/// The adaptive accumulation (AA) map: the paper's Algorithm 1 (docs/representations.md).
///
/// The image is tiled into a grid of blocks; each block accumulates event counts until it is
/// "sharp": when the variance of its non-zero counts
///   C = S2/n − (S1/n)²,  S1 = Σ A, S2 = Σ A², n = #{A > 0}   (O(1) per event)
/// exceeds β at one of the checks made every δt of event time; then its counts freeze. Blocks
/// with fast image motion freeze after a few milliseconds, slow ones keep the whole window, so
/// every region shows its edges equally sharply. Accumulation runs newest first ([ESVO2]; the ICRA
/// code runs forward from the window's start), so a block freezes on the events nearest the tick,
/// aligned with the time surface at the tick.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/events/event.hpp"
#include "aavio/events/events_config.hpp"

namespace aavio::events {

/// How the image is tiled: block (i, j) holds the columns x with x·cols/width = i, likewise rows.
class BlockGrid {
 public:
  BlockGrid(int width, int height, int cols, int rows);
  int BlockOf(int x, int y) const { return block_row_[y] * cols_ + block_col_[x]; }
  int cols() const { return cols_; }
  int rows() const { return rows_; }
  int size() const { return cols_ * rows_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_, cols_, rows_;
  std::vector<int> block_col_, block_row_;
};

struct AaBlock {
  std::vector<std::uint32_t> active;  ///< pixel indices y·width + x with count > 0
  std::int32_t events = 0;            ///< events accumulated
  bool closed = false;                ///< froze before the window's end
  TimeNs span_ns = 0;                 ///< time covered by the accumulated events
  double contrast = 0.0;              ///< C at the freeze (or at the end)
};

struct AaMap {
  TimeNs t_ns = 0;
  cv::Mat counts;  ///< raw coordinates, CV_8UC1, accumulated events per pixel (saturating)
  std::vector<AaBlock> blocks;
  std::int64_t window_events = 0;  ///< events offered
  std::int64_t used_events = 0;    ///< events accumulated
};

/// Variance of the non-zero values of a count image region (the definition; for tests).
double NonZeroVariance(const cv::Mat& counts, const cv::Rect& region);

class AdaptiveAccumulator {
 public:
  AdaptiveAccumulator(int width, int height, const AdaptiveAccumulationConfig& config);

  /// The AA map at t_ns from the events of (t_ns − window, t_ns] among `events` (time-ordered;
  /// older and newer ones are ignored). Overwrites *out, reusing its storage.
  void Build(std::span<const Event> events, TimeNs t_ns, AaMap* out);

  const BlockGrid& grid() const { return grid_; }

 private:
  void BuildContrast(std::span<const Event> window, TimeNs t_ns, AaMap* out);
  void Accumulate(const Event& e, AaMap* out);

  AdaptiveAccumulationConfig config_;
  BlockGrid grid_;
  std::vector<std::uint16_t> counts_;       // exact counts (the output saturates at 255)
  std::vector<std::uint32_t> touched_;      // pixels with counts_ > 0, to reset them cheaply
  std::vector<double> s1_, s2_;             // per block Σ A, Σ A²
  std::vector<TimeNs> first_ns_, last_ns_;  // per block, accumulated events' extent
};

}  // namespace aavio::events
