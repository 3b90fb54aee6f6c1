#pragma once
/// The representation stage of one stereo event camera (docs/architecture.md): events in, one
/// Observation per tick out — time surfaces of both cameras, the negative TS and its gradients,
/// the AA map and the edge samples. Synchronous and driven by data time only: the same events
/// and seed give the same Observation, bit for bit.

#include <cstdint>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/events/adaptive_accumulation.hpp"
#include "aavio/events/events_config.hpp"
#include "aavio/events/observation.hpp"
#include "aavio/events/rectified_image.hpp"
#include "aavio/events/time_surface.hpp"
#include "aavio/geometry/rectification.hpp"

namespace aavio::events {

enum class Camera { kLeft, kRight };

/// What a tick draws beyond the left time surface and its derived images.
struct BuildOptions {
  bool right_ts = true;   ///< the right time surface (static stereo, bootstrap)
  bool edges = true;      ///< the AA map and the edge samples (mapping)
  double decay_ms = 0.0;  ///< the time surfaces' τ; 0: time_surface.decay_ms
};

class RepresentationBuilder {
 public:
  /// `epoch_ns`: a time near the data (the sequence start).
  RepresentationBuilder(const geometry::StereoRectification& rectification, int width, int height,
                        const RepresentationConfig& config, TimeNs epoch_ns);

  /// Adds a camera's events in time order (across calls too); they may run past the next tick.
  Status AddEvents(Camera camera, std::span<const Event> events);

  /// The observation at t_ns: every event up to t_ns must have been added. Ticks increase.
  /// Only mapping needs the right time surface, the AA map and the samples; tracking ticks skip
  /// them with `options` (the images are left empty; every event is still taken in).
  Status Build(TimeNs t_ns, Observation* out, BuildOptions options = {});

  /// Events of both cameras dropped so far by max_buffered_events.
  std::int64_t dropped_events() const { return dropped_events_; }
  /// Events of a camera waiting for the next tick.
  std::size_t buffered_events(Camera camera) const {
    return (camera == Camera::kLeft ? left_ : right_).pending.size();
  }

 private:
  struct CameraState {
    TimeSurface ts;
    ImageRectifier rectifier;
    std::vector<Event> pending;  // added, not yet in the time surface (after the last tick)
    TimeNs newest_added_ns;
  };
  // Moves the pending events up to t_ns into the time surface (and the left window).
  Status Consume(CameraState& camera, TimeNs t_ns, bool keep_window, std::int64_t* consumed);
  // The steps of Build: both time surfaces (the right one if asked), the negative time surface
  // and its gradients, the left events AA and ESVO's selection look at, the AA map, the samples.
  void RenderTimeSurfaces(TimeNs t_ns, const BuildOptions& options, Observation* out);
  void DeriveGradients(Observation* out) const;
  std::span<const Event> RecentLeftEvents(TimeNs t_ns);
  void BuildAaMap(std::span<const Event> recent, TimeNs t_ns, Observation* out);
  void SampleEdges(std::span<const Event> recent, TimeNs t_ns, Observation* out) const;

  RepresentationConfig config_;
  geometry::StereoRectification rectification_;
  CameraState left_, right_;
  std::vector<Event> window_;  // recent left events, for AA and ESVO's selection
  std::int64_t dropped_events_ = 0;
  std::size_t window_begin_ = 0;
  AdaptiveAccumulator accumulator_;
  AaMap aa_;
  TimeNs last_tick_ns_;
  TimeNs epoch_ns_;  // ticks' seeds mix in the time since it: shifting every stamp changes none
  cv::Mat padded_, scratch_binary_;  // raw images with a one-pixel zero border
};

}  // namespace aavio::events
