#pragma once
/// Events from a sequence of rendered intensity images, as ESIM does (Rebecq et al., CoRL 2018):
/// each pixel keeps the log intensity at its last event (the reference); between two renders the
/// log intensity is taken as linear in time, and every crossing of reference ± threshold is an
/// event at the interpolated crossing time. Thresholds differ per pixel (Gaussian spread, fixed
/// for the pixel's life), a refractory period suppresses events that follow too closely, and
/// background-activity noise and hot pixels are added as Poisson processes. Deterministic for a
/// seed; events come out sorted by time (ties by pixel index).

#include <cstdint>
#include <random>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/events/event.hpp"

namespace aavio::sim {

struct EventCameraConfig {
  double threshold_on = 0.25;       ///< mean positive contrast threshold [log intensity]
  double threshold_off = 0.25;      ///< mean negative contrast threshold [log intensity]
  double threshold_sigma = 0.03;    ///< per-pixel spread (std) of both thresholds
  double refractory_us = 100.0;     ///< minimum time between two events of one pixel
  double log_eps = 0.001;           ///< log(I + eps) keeps dark pixels finite
  double noise_rate_hz = 0.1;       ///< background activity per pixel [events/s], both polarities
  double hot_pixel_fraction = 0.0;  ///< share of pixels that fire on their own
  double hot_pixel_rate_hz = 20.0;  ///< their rate [events/s]

  template <typename V>
  void VisitFields(V&& v) {
    v("threshold_on", threshold_on);
    v("threshold_off", threshold_off);
    v("threshold_sigma", threshold_sigma);
    v("refractory_us", refractory_us);
    v("log_eps", log_eps);
    v("noise_rate_hz", noise_rate_hz);
    v("hot_pixel_fraction", hot_pixel_fraction);
    v("hot_pixel_rate_hz", hot_pixel_rate_hz);
  }
  Status Validate() const;
};

class EventGenerator {
 public:
  EventGenerator(int width, int height, const EventCameraConfig& config, std::uint64_t seed);

  /// Starts from an image at t_ns: sets every pixel's reference; emits nothing.
  void Reset(const std::vector<float>& intensity, TimeNs t_ns);
  /// Moves to the next image at t_ns (> the previous one) and appends the events in
  /// (t_prev, t_ns], sorted by time.
  void Step(const std::vector<float>& intensity, TimeNs t_ns, std::vector<events::Event>* out);

  /// Signal (non-noise) events emitted so far, and noise / hot-pixel events.
  std::int64_t signal_events() const { return signal_events_; }
  std::int64_t noise_events() const { return noise_events_; }

 private:
  int width_, height_;
  EventCameraConfig config_;
  std::mt19937_64 rng_;
  std::vector<float> reference_;  // log intensity at the last event
  std::vector<float> last_log_;   // log intensity at the previous render
  std::vector<float> log_;        // log intensity of the current render (scratch)
  std::vector<float> threshold_on_, threshold_off_;
  std::vector<TimeNs> last_event_ns_;
  std::vector<std::uint32_t> hot_pixels_;
  TimeNs last_t_ns_ = 0;
  std::int64_t signal_events_ = 0, noise_events_ = 0;
  std::vector<events::Event> scratch_;
};

}  // namespace aavio::sim
