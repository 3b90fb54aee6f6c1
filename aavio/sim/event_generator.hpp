#pragma once
/// Events from a sequence of rendered intensity images, as ESIM does (Rebecq et al., CoRL 2018),
/// with the pixel and readout effects of a real sensor (v2e, Hu et al., CVPRW 2021;
/// docs/simulator.md gives each effect's source and the values of the named sensor levels):
///   - each pixel keeps the log intensity at its last event (the reference); between two renders
///     the log intensity is taken as linear in time, and every crossing of reference ± threshold
///     is an event at the interpolated crossing time;
///   - ON and OFF thresholds differ per pixel (Gaussian mismatch fixed for the run);
///   - photoreceptor bandwidth: the log intensity the comparator sees is low-passed (first order)
///     with a cutoff proportional to the pixel's intensity, so edges lag and smear in dark regions;
///   - a refractory period after each event;
///   - leak events: each pixel's reference drifts down at its own rate (log-normal spread), which
///     fires ON events in a still scene; shot noise, of either polarity, more frequent in the dark;
///     uniform background activity; hot pixels;
///   - timestamp jitter, and a readout that serialises events at a maximum rate (events are
///     delayed while it is busy, and dropped once they would wait longer than 1 ms).
/// Deterministic for a seed; events come out sorted by time (ties by pixel index). With every
/// added effect off (the defaults) the output is that of the plain ESIM model.

#include <cstdint>
#include <random>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/events/event.hpp"

namespace aavio::sim {

struct EventCameraConfig {
  double threshold_on = 0.25;        ///< mean positive contrast threshold [log intensity]
  double threshold_off = 0.25;       ///< mean negative contrast threshold [log intensity]
  double threshold_sigma = 0.03;     ///< per-pixel mismatch (std) of both thresholds [log]
  double bandwidth_hz = 0.0;         ///< photoreceptor cutoff at intensity 1; 0 = instantaneous
  double refractory_us = 100.0;      ///< minimum time between two events of one pixel
  double log_eps = 0.001;            ///< log(I + eps) keeps dark pixels finite
  double noise_rate_hz = 0.1;        ///< uniform background activity per pixel [events/s]
  double leak_rate_hz = 0.0;         ///< median per-pixel leak (ON) event rate [events/s]
  double leak_rate_spread = 0.0;     ///< std of log10 of the per-pixel leak rate [decades]
  double shot_noise_rate_hz = 0.0;   ///< shot-noise rate per pixel in the dark (¼ of it at I = 1)
  double hot_pixel_fraction = 0.0;   ///< share of pixels that fire on their own
  double hot_pixel_rate_hz = 20.0;   ///< their rate [events/s]
  double timestamp_jitter_us = 0.0;  ///< std of the timestamp error
  double max_rate_mev_s = 0.0;       ///< readout throughput [Mev/s]; 0 = unlimited

  template <typename V>
  void VisitFields(V&& v) {
    v("threshold_on", threshold_on);
    v("threshold_off", threshold_off);
    v("threshold_sigma", threshold_sigma);
    v("bandwidth_hz", bandwidth_hz);
    v("refractory_us", refractory_us);
    v("log_eps", log_eps);
    v("noise_rate_hz", noise_rate_hz);
    v("leak_rate_hz", leak_rate_hz);
    v("leak_rate_spread", leak_rate_spread);
    v("shot_noise_rate_hz", shot_noise_rate_hz);
    v("hot_pixel_fraction", hot_pixel_fraction);
    v("hot_pixel_rate_hz", hot_pixel_rate_hz);
    v("timestamp_jitter_us", timestamp_jitter_us);
    v("max_rate_mev_s", max_rate_mev_s);
  }
  Status Validate() const;
};

class EventGenerator {
 public:
  EventGenerator(int width, int height, const EventCameraConfig& config, std::uint64_t seed);

  /// Starts from an image at t_ns: sets every pixel's reference; emits nothing.
  void Reset(const std::vector<float>& intensity, TimeNs t_ns);
  /// Moves to the next image at t_ns (> the previous one) and appends the events in
  /// (t_prev, t_ns], sorted by time. With a limited readout, events may be stamped after t_ns
  /// (still in time order across steps).
  void Step(const std::vector<float>& intensity, TimeNs t_ns, std::vector<events::Event>* out);

  /// Events of the pixels' comparators emitted so far (the scene, and leak), noise events
  /// (background activity, shot noise, hot pixels) and events the readout dropped.
  std::int64_t signal_events() const { return signal_events_; }
  std::int64_t noise_events() const { return noise_events_; }
  std::int64_t dropped_events() const { return dropped_events_; }

 private:
  void AddNoise(TimeNs t0, double dt_ns, const std::vector<float>& intensity);
  void JitterAndReadOut(TimeNs t0, TimeNs t1);
  void SortScratch();  // by time, ties by pixel index

  int width_;
  EventCameraConfig config_;
  std::mt19937_64 rng_;           // thresholds, background activity, hot pixels
  std::mt19937_64 effects_rng_;   // the effects a plain ESIM lacks (leak, shot noise, jitter)
  std::vector<float> reference_;  // log intensity at the last event
  std::vector<float> last_log_;   // log intensity the comparator saw at the previous render
  std::vector<float> last_raw_;   // unfiltered log intensity of the previous render
  std::vector<float> log_;        // log intensity of the current render (scratch)
  std::vector<float> threshold_on_, threshold_off_;
  std::vector<float> leak_per_ns_;  // per-pixel reference drift [log / ns]
  std::vector<TimeNs> last_event_ns_;
  std::vector<std::uint32_t> hot_pixels_;
  TimeNs last_t_ns_ = 0;
  double readout_free_ns_ = -1e300;  // when the readout can send its next event
  std::int64_t signal_events_ = 0, noise_events_ = 0, dropped_events_ = 0;
  std::vector<events::Event> scratch_;
};

}  // namespace aavio::sim
