#pragma once
/// Measurement noise removed from a recorded camera path before it drives the simulated camera.
///
/// A motion-capture or LiDAR ground truth is a measurement: each pose carries a few tenths of a
/// millimetre and of a degree of noise. A spline that passes through every sample turns that
/// noise into motion — at 200 Hz, 0.2° of jitter becomes tens of degrees per second of angular
/// velocity and several g of acceleration that no real hand-held camera had, and the synthetic
/// IMU and events inherit them. The smoother here removes what the data show to be noise:
///
/// - **Noise level, from the data.** In the third differences of a sampled path, smooth motion
///   is strongly correlated from one sample to the next while white measurement noise is
///   anti-correlated (lag-1 autocovariance −15σ² against a variance of 20σ²). The difference of
///   the two, (γ₀ − γ₁) / 35, estimates σ² with the motion cancelled. It is measured per axis of
///   position and per component of the (sign-aligned) quaternion.
/// - **Smoothing, matched to it.** A Whittaker–Henderson smoother — the discrete form of a
///   quintic smoothing spline: minimise Σ (y − z)² + λ Σ (h³ D³z)², D³ the third divided
///   difference, so uneven stamps are handled — applied to the three position axes with one λ
///   and to the four quaternion components with another (then renormalised). Each λ is chosen
///   so that the rms residual equals the estimated noise (the discrepancy principle): a path
///   without noise is left as it is, a noisy one loses what the noise put in and no more.
///
/// The smoothed path is the ground truth a simulated sequence writes.

#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::sim {

struct PathNoise {
  double position_m = 0.0;     ///< rms per axis
  double rotation_rad = 0.0;   ///< rms rotation angle
};

struct SmoothedPath {
  std::vector<geometry::StampedPose> poses;
  PathNoise noise;                  ///< estimated from the input
  double position_residual_m = 0;   ///< rms per axis, input − smoothed
  double rotation_residual_rad = 0; ///< rms angle between input and smoothed
};

/// The measurement noise of a sampled path (at least 6 poses; fewer give zero).
PathNoise EstimatePathNoise(const std::vector<geometry::StampedPose>& poses);

/// The path with its measurement noise removed. Stamps must increase strictly.
Expected<SmoothedPath> SmoothRecordedPath(const std::vector<geometry::StampedPose>& poses);

}  // namespace aavio::sim
