#pragma once
/// The velocity of a body along a trajectory of poses, and the trajectory sampled at given stamps
/// (poses interpolated, velocities with them): what `aavio run` writes beside its poses, EvSLAM's
/// submissions hold, and the velocity metrics score.

#include <vector>

#include "aavio/common/time.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::geometry {

/// Linear (m/s) and angular (rad/s) velocity in the body's own frame at t_ns.
struct StampedVelocity {
  TimeNs t_ns = 0;
  Eigen::Vector3d v_body_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_body_radps = Eigen::Vector3d::Zero();
  bool valid = false;  ///< false for a pose with no neighbour to differentiate against
};

/// Poses further apart than this many median intervals are a gap: no velocity or interpolation
/// reaches across it (a lost stretch, an event gap, motion capture dropping out).
inline constexpr double kGapMedianIntervals = 5.0;
inline constexpr TimeNs kDefaultVelocityHalfWindowNs = 150 * kNsPerMs;

/// The velocity at every pose: local quadratic least-squares fits over the poses of its segment
/// within ±half_window_ns (at least its nearest neighbours; a line with only two), of the world
/// position (its slope rotated into the body frame, R_world_bodyᵀ·v) and of log(R_iᵀ·R_j) against
/// t_j − t_i (body frame). A centred fit: offline, after the whole trajectory is known. The window
/// trades the tracker's per-tick jitter against the motion's changes: on the hand-held and drone
/// twins the error keeps falling to ±150 ms (kDefaultVelocityHalfWindowNs). Poses sorted by stamp.
std::vector<StampedVelocity> EstimateVelocities(const std::vector<StampedPose>& poses,
                                                TimeNs half_window_ns);

/// The velocity at the newest of `recent` poses from the poses before it within `window_ns` (at
/// least one; none across a gap), for live use (the ROS node's twist): a line, not a quadratic —
/// one-sided, the quadratic's slope at the end amplifies the tracker's jitter (EvSLAM AUC on
/// three twins over 150 ms: line 0.62 / 0.59 / 0.66, quadratic 0.29 / 0.37 / 0.61; the centred
/// quadratic 0.76 / 0.67 / 0.83). It lags accelerating motion by about half the window.
StampedVelocity NewestVelocity(const std::vector<StampedPose>& recent, TimeNs window_ns);

/// A trajectory sampled at requested stamps: poses interpolated (slerp + linear) and velocities
/// linearly between the two poses around each stamp, within a segment; up to one median pose
/// interval beyond a segment's ends, extrapolated at the end's velocity. Stamps elsewhere (before
/// or after the trajectory, inside a gap) are missing.
struct Sampled {
  std::vector<StampedPose> poses;
  std::vector<StampedVelocity> velocities;
  std::vector<TimeNs> missing;  ///< stamps with no pose
};
Sampled SampleAt(const std::vector<StampedPose>& poses,
                 const std::vector<StampedVelocity>& velocities,
                 const std::vector<TimeNs>& stamps_ns);

}  // namespace aavio::geometry
