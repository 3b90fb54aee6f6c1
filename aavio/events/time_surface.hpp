#pragma once
/// The exponential-decay time surface of one camera, made the fast way (docs/representations.md):
/// a dense last-timestamp image updated once per event, and one vectorised pass per tick
///   T(x, t) = exp(−(t − t_last(x)) / τ),  stored as round(255 · T) (uint8; never hit → 0).
/// Everything here is in raw (distorted) sensor coordinates; `RectifiedImages` moves images to the
/// rectified plane.

#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/events/event.hpp"

namespace aavio::events {

class TimeSurface {
 public:
  /// `epoch_ns`: any time near the data (e.g. the sequence start). Stamps are kept as float
  /// seconds relative to an epoch that follows the data (moved forward every second), so they
  /// keep a resolution of about 0.1 µs whatever the absolute time; values are exact to ±1 level.
  TimeSurface(int width, int height, TimeNs epoch_ns);

  /// Records events (time-ordered, not older than the newest recorded one). Events outside the
  /// sensor are an error: the readers drop them, so one here is a bug upstream.
  Status Insert(std::span<const Event> events);

  /// The time surface at t_ns (≥ every recorded event), raw coordinates, CV_8UC1. `out` may be
  /// a view of the right size into a larger image.
  void Render(TimeNs t_ns, double decay_ms, cv::Mat* out) const;

  TimeNs newest_ns() const { return newest_ns_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  TimeNs epoch_ns_;
  TimeNs newest_ns_;
  void MoveEpoch(TimeNs epoch_ns);

  std::vector<float> t_last_s_;  // per pixel, seconds since the epoch; very negative = never
};

/// The definition, pixel by pixel over a list of events (for tests and as the reference).
cv::Mat BruteForceTimeSurface(std::span<const Event> events, int width, int height, TimeNs t_ns,
                              double decay_ms);

}  // namespace aavio::events
