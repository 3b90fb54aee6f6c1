#pragma once
/// Built-in parametric motions, deterministic from a seed. World frame: the first camera pose is
/// the identity; the camera looks along +z with +y towards the ground, so gravity is +y.

#include <vector>

#include "aavio/geometry/pose_buffer.hpp"

namespace aavio::sim {

/// Hand-held 6-DoF: a slow walk forward plus smooth sways of ±0.3 m and ±20° (rpg-like).
std::vector<geometry::StampedPose> HandHeldMotion(double duration_s, std::uint64_t seed);
/// Urban driving at 5–12 m/s with turns and one stop, camera 1.4 m above a flat road (DSEC-like).
std::vector<geometry::StampedPose> DrivingMotion(double duration_s, std::uint64_t seed);
/// Drone flight in a hall: take-off-free hovering with translations of ±1.5 m and yaw (MVSEC).
std::vector<geometry::StampedPose> DroneMotion(double duration_s, std::uint64_t seed);

/// Smooth analytic 6-DoF motion, unlike the random-walk ones: each axis one sinusoid (periods
/// 3–6 s, random phases; ±0.25 m across, ±0.1 m vertically, ±0.2 m in depth, ±5–8° of each
/// rotation), already moving at t = 0; 0.3–0.45 m/s on average, up to 5–17 °/s per axis.
std::vector<geometry::StampedPose> SinusoidMotion(double duration_s, std::uint64_t seed);

/// Gravity in the world frame of these motions [m/s²].
inline Eigen::Vector3d BuiltInGravity() {
  return {0.0, 9.81, 0.0};
}

}  // namespace aavio::sim
