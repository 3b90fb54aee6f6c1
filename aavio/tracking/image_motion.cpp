#include "aavio/tracking/image_motion.hpp"

#include <algorithm>
#include <vector>

namespace aavio::tracking {

double MedianImageSpeed(std::span<const Eigen::Vector3d> points_world,
                        const geometry::RigidTransform& T_world_a,
                        const geometry::RigidTransform& T_world_b, const Camera& camera,
                        double dt_s) {
  constexpr std::size_t kMaxPoints = 200;
  if (points_world.empty() || dt_s <= 0.0) return 0.0;
  const geometry::RigidTransform T_a_world = T_world_a.Inverse(), T_b_world = T_world_b.Inverse();
  const std::size_t stride = std::max<std::size_t>(1, points_world.size() / kMaxPoints);
  std::vector<double> moved;
  moved.reserve(kMaxPoints + 1);
  for (std::size_t i = 0; i < points_world.size(); i += stride) {
    const Eigen::Vector3d a = T_a_world * points_world[i], b = T_b_world * points_world[i];
    if (a.z() <= 1e-6 || b.z() <= 1e-6) continue;
    const Eigen::Vector2d d = a.head<2>() / a.z() - b.head<2>() / b.z();
    moved.push_back(camera.f * d.norm());
  }
  if (moved.empty()) return 0.0;
  const auto mid = moved.begin() + static_cast<std::ptrdiff_t>(moved.size() / 2);
  std::nth_element(moved.begin(), mid, moved.end());
  return *mid / dt_s;
}

void TimeSurfaceDecay::AddSpeed(double px_per_s) {
  speeds_.push_back(px_per_s);
  if (speeds_.size() > kTicks) speeds_.pop_front();
}

double TimeSurfaceDecay::decay_ms() const {
  if (travel_px_ <= 0.0 || speeds_.empty()) return decay_ms_;
  std::vector<double> sorted(speeds_.begin(), speeds_.end());
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  const double max_ms = kMaxDecayFactor * decay_ms_;
  if (*mid * max_ms * 1e-3 <= travel_px_) return max_ms;
  return std::clamp(1e3 * travel_px_ / *mid, decay_ms_, max_ms);
}

}  // namespace aavio::tracking
