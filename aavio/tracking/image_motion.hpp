#pragma once
/// How fast the scene moves across the image: the median speed [px/s] of map points projected
/// at two tracked poses. It sets the time surface's decay (events/events_config.hpp,
/// `time_surface.min_edge_travel_px`): an edge must travel a few pixels within τ to draw a
/// gradient that registration can follow, whatever the scene's event density.

#include <Eigen/Core>
#include <deque>
#include <span>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/tracking/registration.hpp"

namespace aavio::tracking {

/// Median image speed [px/s] of `points_world` (at most ~200 of them, evenly strided) between
/// the poses T_world_a and T_world_b, `dt_s` apart; 0 when no point is in front of both.
double MedianImageSpeed(std::span<const Eigen::Vector3d> points_world,
                        const geometry::RigidTransform& T_world_a,
                        const geometry::RigidTransform& T_world_b, const Camera& camera,
                        double dt_s);

/// The decay τ of the next tick's time surface: the configured τ, lengthened where the image
/// moves slowly so that edges travel `travel_px` within it, up to kMaxDecayFactor times the
/// configured τ. The speed is the median of the last few tracked ticks.
class TimeSurfaceDecay {
 public:
  static constexpr double kMaxDecayFactor = 10.0;
  static constexpr std::size_t kTicks = 5;

  TimeSurfaceDecay(double decay_ms, double travel_px)
      : decay_ms_(decay_ms), travel_px_(travel_px) {}
  void AddSpeed(double px_per_s);
  /// Forgets the speeds (a new map: the next ticks start from the configured τ).
  void Reset() { speeds_.clear(); }
  double decay_ms() const;

 private:
  double decay_ms_, travel_px_;
  std::deque<double> speeds_;
};

}  // namespace aavio::tracking
