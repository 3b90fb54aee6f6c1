#pragma once
/// How far away the scene is, measured on the first moments of a sequence before anything is
/// configured: both cameras' time surfaces at one instant, matched by SGM over every disparity
/// half the image allows, at the edges the events show. What a preset is chosen from when none
/// is named (a wide rig in a room is no car's).

#include <optional>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/events/event.hpp"
#include "aavio/events/representation_builder.hpp"
#include "aavio/geometry/stereo_rig.hpp"

namespace aavio::pipeline {

struct SceneDepth {
  std::vector<double> depths_m;  ///< the edges' depths, ascending
  double at_s = 0.0;             ///< seconds after the probe's start where it was measured

  double median_m() const { return depths_m.empty() ? 0.0 : depths_m[depths_m.size() / 2]; }
  /// The share of the edges from near_m to far_m.
  double ShareWithin(double near_m, double far_m) const;
};

class SceneDepthProbe {
 public:
  /// Events this long before the measuring instant are what the time surfaces hold.
  static constexpr TimeNs kWindowNs = 300'000'000;

  /// `start_ns`: where the events to measure begin.
  SceneDepthProbe(const geometry::StereoRig& rig, TimeNs start_ns);

  /// Adds a camera's events in time order (across calls too).
  Status AddEvents(events::Camera camera, std::span<const events::Event> events);

  /// The scene's depth at t_ns (every event up to it added), or nothing when too few edges were
  /// matched (a still camera, a dark or empty view). Times increase across calls.
  Expected<std::optional<SceneDepth>> Measure(TimeNs t_ns);

 private:
  geometry::StereoRig rig_;
  TimeNs start_ns_;
  events::RepresentationBuilder builder_;
};

}  // namespace aavio::pipeline
