#include "aavio/events/time_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aavio/common/fast_math.hpp"
#include "aavio/common/format.hpp"

namespace aavio::events {
namespace {
constexpr double kNever = -1e12;  // seconds before the epoch: decays to exactly 0
}  // namespace

TimeSurface::TimeSurface(int width, int height, TimeNs epoch_ns)
    : width_(width),
      height_(height),
      epoch_ns_(epoch_ns),
      newest_ns_(std::numeric_limits<TimeNs>::min()),
      t_last_s_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), kNever) {}

Status TimeSurface::Insert(std::span<const Event> events) {
  for (const Event& e : events) {
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
    t_last_s_[static_cast<std::size_t>(e.y) * static_cast<std::size_t>(width_) + e.x] =
        NsToSeconds(e.t_ns - epoch_ns_);
  }
  return Status::Ok();
}

void TimeSurface::Render(TimeNs t_ns, double decay_ms, cv::Mat* out) const {
  out->create(height_, width_, CV_8UC1);
  const std::size_t n = t_last_s_.size();
  exponent_.resize(n);
  const double t_s = NsToSeconds(t_ns - epoch_ns_);
  const double inv_tau = 1e3 / decay_ms;
  // Two simple loops the compiler vectorises: the exponent in double (stamps are large), then
  // exp and the 0–255 scaling in float.
  const double* t_last = t_last_s_.data();
  float* x = exponent_.data();
  for (std::size_t i = 0; i < n; ++i)
    x[i] = static_cast<float>(std::min(0.0, std::max(-100.0, (t_last[i] - t_s) * inv_tau)));
  std::uint8_t* dst = out->ptr<std::uint8_t>();
  for (std::size_t i = 0; i < n; ++i)
    dst[i] = static_cast<std::uint8_t>(255.0f * FastExpNonPositive(x[i]) + 0.5f);
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
