#pragma once
/// The age of the events at the map's edges, and the time-surface decay that follows from it
/// (events/events_config.hpp, `time_surface.adaptive_decay`). A time surface draws an edge as the
/// trail of its newest events; where the camera moves slowly or the scene has few, weak edges, an
/// edge fires a pixel only every few tens of milliseconds and a fixed τ of 30 ms shows it faded,
/// so registration has little to follow. τ is kept at least as long as the events at the edges
/// the map lies on are old: the median edge then shows at e⁻¹ of full scale, whatever the scene's
/// event density. Measured, not assumed: in the rooms and streets the edges are 6–10 ms old and
/// τ stays as configured but for their slowest stretches.

#include <Eigen/Core>
#include <deque>
#include <opencv2/core/mat.hpp>
#include <span>

#include "aavio/geometry/rigid_transform.hpp"
#include "aavio/tracking/registration.hpp"

namespace aavio::tracking {

/// Median age [ms] of the newest event at the map's edges: map points (at most ~200, strided)
/// projected at T_world_cam onto the time surface `ts` (CV_8UC1, rendered with `decay_ms`), each
/// reading the freshest value of its 3×3 neighbourhood (a point may sit a pixel off its edge),
/// turned back into an age. Faded or empty pixels count as AdaptiveDecay::kMaxFactor τ old;
/// -1 when no point is in view.
double MedianEdgeAgeMs(std::span<const Eigen::Vector3d> points_world,
                       const geometry::RigidTransform& T_world_cam, const Camera& camera,
                       const cv::Mat& ts, double decay_ms);

/// τ for the next tick: the median of the last kTicks edge ages, at least the configured τ and at
/// most kMaxFactor times it; the configured τ until an age is known or when adaptation is off.
class AdaptiveDecay {
 public:
  static constexpr double kMaxFactor = 10.0;
  static constexpr std::size_t kTicks = 20;

  AdaptiveDecay(double decay_ms, bool enabled) : decay_ms_(decay_ms), enabled_(enabled) {}
  void AddEdgeAge(double age_ms);
  double decay_ms() const;

 private:
  double decay_ms_;
  bool enabled_;
  std::deque<double> ages_;
};

}  // namespace aavio::tracking
