#include "aavio/events/time_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aavio/common/fast_math.hpp"
#include "aavio/common/format.hpp"
#include "aavio/common/vector_clones.hpp"

namespace aavio::events {
namespace {
constexpr float kNever = -1e30f;        // seconds before the epoch: decays to exactly 0
constexpr TimeNs kEpochSpan = kNsPerS;  // how far the data may run ahead of the epoch

// One row: exponent, exp, 0–255, in a loop the compiler vectorises; built for AVX2 and for the
// x86-64 baseline, picked at load time (the same IEEE operations, so the same bytes either way).
AAVIO_AVX2_CLONES void RenderRow(const float* t_last, std::uint8_t* dst, int width, float t_s,
                                 float inv_tau) {
  for (int x = 0; x < width; ++x) {
    const float e = std::clamp((t_last[x] - t_s) * inv_tau, -87.0f, 0.0f);
    dst[x] = static_cast<std::uint8_t>(static_cast<int>(255.0f * FastExpNonPositive(e) + 0.5f));
  }
}

}  // namespace

TimeSurface::TimeSurface(int width, int height, TimeNs epoch_ns)
    : width_(width),
      height_(height),
      epoch_ns_(epoch_ns),
      newest_ns_(std::numeric_limits<TimeNs>::min()),
      t_last_s_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), kNever) {}

Status TimeSurface::Insert(std::span<const Event> events) {
  // Events fall anywhere on the sensor: each one's pixel is asked for a few events ahead.
  constexpr std::size_t kAhead = 16;
  for (std::size_t i = 0; i < events.size(); ++i) {
    if (i + kAhead < events.size()) {
      const Event& next = events[i + kAhead];
      if (next.x < width_ && next.y < height_) {
        __builtin_prefetch(t_last_s_.data() +
                               static_cast<std::size_t>(next.y) * static_cast<std::size_t>(width_) +
                               next.x,
                           1);
      }
    }
    const Event& e = events[i];
    if (e.x >= width_ || e.y >= height_) {
      return InvalidArgument(
          StrFormat("event at (%d, %d) lies outside the %d×%d sensor", e.x, e.y, width_, height_));
    }
    if (e.t_ns < newest_ns_) {
      return InvalidArgument("events reach the time surface out of order (" +
                             FormatSecondsNs(e.t_ns) + " s after " + FormatSecondsNs(newest_ns_) +
                             " s)");
    }
    newest_ns_ = e.t_ns;
    if (e.t_ns - epoch_ns_ > kEpochSpan) MoveEpoch(e.t_ns);
    t_last_s_[static_cast<std::size_t>(e.y) * static_cast<std::size_t>(width_) + e.x] =
        static_cast<float>(NsToSeconds(e.t_ns - epoch_ns_));
  }
  return Status::Ok();
}

void TimeSurface::MoveEpoch(TimeNs epoch_ns) {
  const float shift = static_cast<float>(NsToSeconds(epoch_ns - epoch_ns_));
  for (float& t : t_last_s_)
    t -= shift;
  epoch_ns_ = epoch_ns;
}

void TimeSurface::Render(TimeNs t_ns, double decay_ms, cv::Mat* out) const {
  out->create(height_, width_, CV_8UC1);
  const float t_s = static_cast<float>(NsToSeconds(t_ns - epoch_ns_));
  const float inv_tau = static_cast<float>(1e3 / decay_ms);
  // `out` may be a view (the interior of a padded image): rows are addressed by its step.
  for (int y = 0; y < height_; ++y) {
    RenderRow(t_last_s_.data() + static_cast<std::size_t>(y) * width_, out->ptr<std::uint8_t>(y),
              width_, t_s, inv_tau);
  }
}

cv::Mat BruteForceTimeSurface(std::span<const Event> events, int width, int height, TimeNs t_ns,
                              double decay_ms) {
  cv::Mat ts(height, width, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // The newest event at (x, y) not after t_ns.
      TimeNs newest = std::numeric_limits<TimeNs>::min();
      for (const Event& e : events) {
        if (e.x == x && e.y == y && e.t_ns <= t_ns) newest = std::max(newest, e.t_ns);
      }
      if (newest == std::numeric_limits<TimeNs>::min()) continue;
      const double value = 255.0 * std::exp(-NsToSeconds(t_ns - newest) * 1e3 / decay_ms);
      ts.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::lround(value));
    }
  }
  return ts;
}

}  // namespace aavio::events
