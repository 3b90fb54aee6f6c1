#include "aavio/sim/event_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "aavio/common/fast_math.hpp"

namespace aavio::sim {

namespace {

/// The readout drops an event that would wait longer than this for its turn (a full FIFO).
constexpr double kReadoutMaxWaitNs = 1e6;
/// Shot noise in a fully lit pixel relative to a dark one (v2e's SHOT_NOISE_INTEN_FACTOR).
constexpr float kShotNoiseBrightFactor = 0.25f;
/// The photoreceptor's cutoff never falls below this share of its full-light value.
constexpr float kMinBandwidthShare = 0.01f;

}  // namespace

Status EventCameraConfig::Validate() const {
  FieldChecker check;
  check.InRange("threshold_on", threshold_on, 0.01, 5.0)
      .InRange("threshold_off", threshold_off, 0.01, 5.0)
      .InRange("threshold_sigma", threshold_sigma, 0.0, 1.0)
      .InRange("bandwidth_hz", bandwidth_hz, 0.0, 1e6)
      .InRange("refractory_us", refractory_us, 0.0, 1e6)
      .InRange("log_eps", log_eps, 1e-9, 1.0)
      .InRange("noise_rate_hz", noise_rate_hz, 0.0, 1e4)
      .InRange("leak_rate_hz", leak_rate_hz, 0.0, 1e3)
      .InRange("leak_rate_spread", leak_rate_spread, 0.0, 3.0)
      .InRange("shot_noise_rate_hz", shot_noise_rate_hz, 0.0, 1e4)
      .InRange("hot_pixel_fraction", hot_pixel_fraction, 0.0, 0.1)
      .InRange("hot_pixel_rate_hz", hot_pixel_rate_hz, 0.0, 1e5)
      .InRange("timestamp_jitter_us", timestamp_jitter_us, 0.0, 1e5)
      .InRange("max_rate_mev_s", max_rate_mev_s, 0.0, 1e4);
  if (bandwidth_hz > 0.0 && bandwidth_hz < 1.0) {
    return InvalidArgument("bandwidth_hz: " + config_detail::FormatDouble(bandwidth_hz) +
                           " Hz is below any real photoreceptor's; use 0 (instantaneous) or ≥ 1");
  }
  if (max_rate_mev_s > 0.0 && max_rate_mev_s < 0.01) {
    return InvalidArgument("max_rate_mev_s: " + config_detail::FormatDouble(max_rate_mev_s) +
                           " Mev/s would drop nearly every event; use 0 (unlimited) or ≥ 0.01");
  }
  return check.status();
}

EventGenerator::EventGenerator(int width, int height, const EventCameraConfig& config,
                               std::uint64_t seed)
    : width_(width), config_(config), rng_(seed), effects_rng_(seed ^ 0x9E3779B97F4A7C15ULL) {
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
  if (config.leak_rate_hz > 0.0) {
    // Leak: the reference falls by one ON threshold every 1/rate seconds; rates spread
    // log-normally over the pixels (v2e's leak-rate spread).
    std::normal_distribution<double> decades(0.0, config.leak_rate_spread);
    leak_per_ns_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double rate = config.leak_rate_hz * std::pow(10.0, decades(effects_rng_));
      leak_per_ns_[i] = static_cast<float>(rate * static_cast<double>(threshold_on_[i]) * 1e-9);
    }
  }
}

void EventGenerator::Reset(const std::vector<float>& intensity, TimeNs t_ns) {
  const std::size_t n = intensity.size();
  reference_.resize(n);
  last_log_.resize(n);
  last_raw_.resize(n);
  const float eps = static_cast<float>(config_.log_eps);
  for (std::size_t i = 0; i < n; ++i)
    reference_[i] = last_log_[i] = last_raw_[i] = FastLog(intensity[i] + eps);
  if (!leak_per_ns_.empty()) {
    // A sensor switched on long ago: each pixel is somewhere between its two thresholds, so the
    // leak events of a still scene do not all come at once.
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (std::size_t i = 0; i < n; ++i)
      reference_[i] -=
          unit(effects_rng_) * (threshold_on_[i] + threshold_off_[i]) - threshold_off_[i];
  }
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
  if (config_.bandwidth_hz > 0.0) {
    // First-order low-pass, exact for a log intensity linear over the step: for input u going
    // from u0 to u1 at slope s, y1 = u1 − sτ + (y0 − u0 + sτ)·e^(−dt/τ); τ = 1 / (2π f_c) with the
    // cutoff f_c proportional to the pixel's intensity (photocurrent), as in v2e.
    const float dt_f = static_cast<float>(dt);
    const float tau_full_ns =
        static_cast<float>(1e9 / (2.0 * std::numbers::pi * config_.bandwidth_hz));
    for (std::size_t i = 0; i < n; ++i) {
      const float u0 = last_raw_[i], u1 = log_[i];
      last_raw_[i] = u1;
      const float tau = tau_full_ns / std::max(intensity[i], kMinBandwidthShare);
      const float s_tau = (u1 - u0) / dt_f * tau;
      log_[i] = u1 - s_tau + (last_log_[i] - u0 + s_tau) * FastExpNonPositive(-dt_f / tau);
    }
  }
  const bool leaks = !leak_per_ns_.empty();
  const float dt_ns = static_cast<float>(dt);

  for (std::size_t i = 0; i < n; ++i) {
    const float l0 = last_log_[i];
    const float l1 = log_[i];
    last_log_[i] = l1;
    float& ref = reference_[i];
    if (leaks) ref -= leak_per_ns_[i] * dt_ns;
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

  AddNoise(t0, dt, intensity);
  SortScratch();
  if (config_.timestamp_jitter_us > 0.0 || config_.max_rate_mev_s > 0.0) JitterAndReadOut(t0, t_ns);
  out->insert(out->end(), scratch_.begin(), scratch_.end());
  last_t_ns_ = t_ns;
}

void EventGenerator::SortScratch() {
  std::stable_sort(scratch_.begin(), scratch_.end(),
                   [this](const events::Event& a, const events::Event& b) {
                     if (a.t_ns != b.t_ns) return a.t_ns < b.t_ns;
                     return a.y * width_ + a.x < b.y * width_ + b.x;
                   });
}

void EventGenerator::AddNoise(TimeNs t0, double dt, const std::vector<float>& intensity) {
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

  // Shot noise: Poisson at the dark rate over all pixels, thinned by each pixel's intensity
  // (a lit pixel keeps a quarter of it). The refractory period applies; the reference stays (the
  // pixel resets to its noisy level, which returns to the signal by less than a threshold).
  if (config_.shot_noise_rate_hz <= 0.0) return;
  const TimeNs refractory_ns = static_cast<TimeNs>(config_.refractory_us * 1e3);
  const std::int64_t candidates = std::poisson_distribution<std::int64_t>(
      config_.shot_noise_rate_hz * pixels * seconds)(effects_rng_);
  for (std::int64_t k = 0; k < candidates; ++k) {
    const std::uint32_t i = any_pixel(effects_rng_);
    const double keep = static_cast<double>(1.0f - (1.0f - kShotNoiseBrightFactor) *
                                                       std::clamp(intensity[i], 0.0f, 1.0f));
    const double u = unit(effects_rng_);
    const bool on = unit(effects_rng_) < 0.5;
    const TimeNs t = t0 + std::max<TimeNs>(1, static_cast<TimeNs>(unit(effects_rng_) * dt));
    if (u >= keep || std::llabs(t - last_event_ns_[i]) < refractory_ns) continue;
    last_event_ns_[i] = std::max(last_event_ns_[i], t);
    scratch_.push_back({t, static_cast<std::uint16_t>(i % static_cast<std::uint32_t>(width_)),
                        static_cast<std::uint16_t>(i / static_cast<std::uint32_t>(width_)),
                        static_cast<std::uint8_t>(on ? 1 : 0)});
    ++noise_events_;
  }
}

void EventGenerator::JitterAndReadOut(TimeNs t0, TimeNs t1) {
  if (config_.timestamp_jitter_us > 0.0) {
    // Jitter stays inside the step so that steps remain in time order.
    std::normal_distribution<double> jitter(0.0, config_.timestamp_jitter_us * 1e3);
    for (events::Event& e : scratch_) {
      e.t_ns = std::clamp<TimeNs>(e.t_ns + static_cast<TimeNs>(std::llround(jitter(effects_rng_))),
                                  t0 + 1, t1);
    }
    SortScratch();
  }
  if (config_.max_rate_mev_s <= 0.0) return;
  // The readout sends one event every period; an event waits for its turn, or is dropped when it
  // would wait too long. Its timestamp is the time it is sent (monotonic across steps).
  const double period_ns = 1e3 / config_.max_rate_mev_s;
  std::size_t kept = 0;
  for (const events::Event& e : scratch_) {
    const double send_ns = std::max(static_cast<double>(e.t_ns), readout_free_ns_);
    if (send_ns - static_cast<double>(e.t_ns) > kReadoutMaxWaitNs) {
      ++dropped_events_;
      continue;
    }
    readout_free_ns_ = send_ns + period_ns;
    events::Event sent = e;
    sent.t_ns = static_cast<TimeNs>(std::ceil(send_ns));
    scratch_[kept++] = sent;
  }
  scratch_.resize(kept);
}

}  // namespace aavio::sim
