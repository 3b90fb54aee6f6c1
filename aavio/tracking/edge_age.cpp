#include "aavio/tracking/edge_age.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace aavio::tracking {
namespace {

double Median(std::vector<double> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace

double MedianEdgeAgeMs(std::span<const Eigen::Vector3d> points_world,
                       const geometry::RigidTransform& T_world_cam, const Camera& camera,
                       const cv::Mat& ts, double decay_ms) {
  constexpr std::size_t kMaxPoints = 200;
  if (points_world.empty() || ts.empty()) return -1.0;
  const double faded_ms = AdaptiveDecay::kMaxFactor * decay_ms;
  const geometry::RigidTransform T_cam_world = T_world_cam.Inverse();
  const std::size_t stride = std::max<std::size_t>(1, points_world.size() / kMaxPoints);
  std::vector<double> ages;
  ages.reserve(kMaxPoints + 1);
  for (std::size_t i = 0; i < points_world.size(); i += stride) {
    const Eigen::Vector3d q = T_cam_world * points_world[i];
    if (q.z() <= 1e-6) continue;
    const double u = camera.f * q.x() / q.z() + camera.cx, v = camera.f * q.y() / q.z() + camera.cy;
    if (!(u >= 1.0 && v >= 1.0 && u < ts.cols - 2.0 && v < ts.rows - 2.0)) continue;
    const int x = static_cast<int>(std::lround(u)), y = static_cast<int>(std::lround(v));
    int freshest = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      const std::uint8_t* row = ts.ptr<std::uint8_t>(y + dy);
      for (int dx = -1; dx <= 1; ++dx)
        freshest = std::max<int>(freshest, row[x + dx]);
    }
    ages.push_back(freshest == 0 ? faded_ms
                                 : std::min(faded_ms, -decay_ms * std::log(freshest / 255.0)));
  }
  return ages.empty() ? -1.0 : Median(std::move(ages));
}

void AdaptiveDecay::AddEdgeAge(double age_ms) {
  ages_.push_back(age_ms);
  if (ages_.size() > kTicks) ages_.pop_front();
}

double AdaptiveDecay::decay_ms() const {
  if (!enabled_ || ages_.empty()) return decay_ms_;
  return std::clamp(Median({ages_.begin(), ages_.end()}), decay_ms_, kMaxFactor * decay_ms_);
}

}  // namespace aavio::tracking
