#include "aavio/sim/event_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aavio/common/fast_math.hpp"

namespace aavio::sim {

Status EventCameraConfig::Validate() const {
  FieldChecker check;
  check.InRange("threshold_on", threshold_on, 0.01, 5.0)
      .InRange("threshold_off", threshold_off, 0.01, 5.0)
      .InRange("threshold_sigma", threshold_sigma, 0.0, 1.0)
      .NonNegative("refractory_us", refractory_us)
      .InRange("log_eps", log_eps, 1e-9, 1.0)
      .InRange("noise_rate_hz", noise_rate_hz, 0.0, 1e4)
      .InRange("hot_pixel_fraction", hot_pixel_fraction, 0.0, 0.1)
      .InRange("hot_pixel_rate_hz", hot_pixel_rate_hz, 0.0, 1e5);
  return check.status();
}

EventGenerator::EventGenerator(int width, int height, const EventCameraConfig& config,
                               std::uint64_t seed)
    : width_(width), height_(height), config_(config), rng_(seed) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  threshold_on_.resize(n);
  threshold_off_.resize(n);
  std::normal_distribution<double> spread(0.0, config.threshold_sigma);
  // Thresholds never fall below a fifth of their mean (a sensor has a minimum contrast).
  for (std::size_t i = 0; i < n; ++i) {
    threshold_on_[i] =
        static_cast<float>(std::max(config.threshold_on + spread(rng_), 0.2 * config.threshold_on));
    threshold_off_[i] = static_cast<float>(
        std::max(config.threshold_off + spread(rng_), 0.2 * config.threshold_off));
  }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (unit(rng_) < config.hot_pixel_fraction)
      hot_pixels_.push_back(static_cast<std::uint32_t>(i));
  }
  last_event_ns_.assign(n, std::numeric_limits<TimeNs>::min() / 2);
}

void EventGenerator::Reset(const std::vector<float>& intensity, TimeNs t_ns) {
  const std::size_t n = intensity.size();
  reference_.resize(n);
  last_log_.resize(n);
  const float eps = static_cast<float>(config_.log_eps);
  for (std::size_t i = 0; i < n; ++i)
    reference_[i] = last_log_[i] = FastLog(intensity[i] + eps);
  last_t_ns_ = t_ns;
}

void EventGenerator::Step(const std::vector<float>& intensity, TimeNs t_ns,
                          std::vector<events::Event>* out) {
  const TimeNs t0 = last_t_ns_;
  const double dt = static_cast<double>(t_ns - t0);
  const float eps = static_cast<float>(config_.log_eps);
  const TimeNs refractory_ns = static_cast<TimeNs>(config_.refractory_us * 1e3);
  scratch_.clear();

  // The logarithm in its own loop, which the compiler vectorises (most of a step's cost).
  const std::size_t n = intensity.size();
  log_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    log_[i] = FastLog(intensity[i] + eps);

  for (std::size_t i = 0; i < n; ++i) {
    const float l0 = last_log_[i];
    const float l1 = log_[i];
    last_log_[i] = l1;
    float& ref = reference_[i];
    const float delta = l1 - ref;
    if (delta < threshold_on_[i] && -delta < threshold_off_[i]) continue;  // the common case
    const bool on = delta > 0.0f;
    const float c = on ? threshold_on_[i] : -threshold_off_[i];
    const float slope = l1 - l0;
    const std::uint16_t x = static_cast<std::uint16_t>(i % static_cast<std::size_t>(width_));
    const std::uint16_t y = static_cast<std::uint16_t>(i / static_cast<std::size_t>(width_));
    // Every level ref + k·c crossed between l0 and l1, at its linearly interpolated time.
    while (on ? (l1 - ref >= c) : (l1 - ref <= c)) {
      ref += c;
      const double fraction =
          slope != 0.0f ? std::clamp(static_cast<double>((ref - l0) / slope), 0.0, 1.0) : 1.0;
      const TimeNs t = t0 + std::max<TimeNs>(1, static_cast<TimeNs>(std::llround(fraction * dt)));
      if (t - last_event_ns_[i] < refractory_ns) continue;  // the pixel is still resetting
      last_event_ns_[i] = t;
      scratch_.push_back({t, x, y, static_cast<std::uint8_t>(on ? 1 : 0)});
    }
  }
  signal_events_ += static_cast<std::int64_t>(scratch_.size());

  // Background activity and hot pixels: Poisson processes, uniform in time over the step.
  const double seconds = dt * 1e-9;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto add_noise = [&](double mean, auto pick_pixel) {
    if (mean <= 0.0) return;
    const std::int64_t count = std::poisson_distribution<std::int64_t>(mean)(rng_);
    for (std::int64_t k = 0; k < count; ++k) {
      const std::uint32_t i = pick_pixel();
      const TimeNs t = t0 + std::max<TimeNs>(1, static_cast<TimeNs>(unit(rng_) * dt));
      scratch_.push_back({t, static_cast<std::uint16_t>(i % static_cast<std::uint32_t>(width_)),
                          static_cast<std::uint16_t>(i / static_cast<std::uint32_t>(width_)),
                          static_cast<std::uint8_t>(unit(rng_) < 0.5 ? 1 : 0)});
      ++noise_events_;
    }
  };
  const std::uint32_t pixels = static_cast<std::uint32_t>(intensity.size());
  std::uniform_int_distribution<std::uint32_t> any_pixel(0, pixels - 1);
  add_noise(config_.noise_rate_hz * pixels * seconds, [&] { return any_pixel(rng_); });
  if (!hot_pixels_.empty()) {
    std::uniform_int_distribution<std::size_t> any_hot(0, hot_pixels_.size() - 1);
    add_noise(config_.hot_pixel_rate_hz * static_cast<double>(hot_pixels_.size()) * seconds,
              [&] { return hot_pixels_[any_hot(rng_)]; });
  }

  std::stable_sort(scratch_.begin(), scratch_.end(),
                   [this](const events::Event& a, const events::Event& b) {
                     if (a.t_ns != b.t_ns) return a.t_ns < b.t_ns;
                     return a.y * width_ + a.x < b.y * width_ + b.x;
                   });
  out->insert(out->end(), scratch_.begin(), scratch_.end());
  last_t_ns_ = t_ns;
}

}  // namespace aavio::sim
