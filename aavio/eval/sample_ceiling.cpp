#include "aavio/eval/sample_ceiling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace aavio::eval {

namespace {
/// More cycles than any fusion FIFO holds (rpg: 40 frames or 5000 points).
constexpr std::size_t kMaxStoredCycles = 64;
}  // namespace

SampleCeiling::SampleCeiling(const PinholeCamera& camera, double min_depth_m, double max_depth_m,
                             int cell_side)
    : camera_(camera),
      min_depth_m_(min_depth_m),
      max_depth_m_(max_depth_m),
      cell_lo_(cell_side >= 3 ? -1 : 0),
      scored_(camera) {}

void SampleCeiling::AddCycle(std::span<const Eigen::Vector2f> samples_px, const cv::Mat& gt_depth_m,
                             const geometry::RigidTransform& T_world_cam) {
  // One point per cell, each at its own true depth; a cell shared by two samples counts once.
  cv::Mat taken(gt_depth_m.size(), CV_8UC1, cv::Scalar(0));
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector2f& x : samples_px) {
    const int u = static_cast<int>(std::lround(x.x())), v = static_cast<int>(std::lround(x.y()));
    if (u < 0 || v < 0 || u >= gt_depth_m.cols || v >= gt_depth_m.rows) continue;
    const double z_sample = gt_depth_m.at<float>(v, u);
    if (!(z_sample >= min_depth_m_ && z_sample <= max_depth_m_)) continue;
    const int x0 = static_cast<int>(std::floor(x.x())), y0 = static_cast<int>(std::floor(x.y()));
    for (int dy = cell_lo_; dy <= 1; ++dy) {
      for (int dx = cell_lo_; dx <= 1; ++dx) {
        const int cx = x0 + dx, cy = y0 + dy;
        if (cx < 0 || cy < 0 || cx >= gt_depth_m.cols || cy >= gt_depth_m.rows) continue;
        const double z = gt_depth_m.at<float>(cy, cx);
        if (!(z > 0.0) || taken.at<std::uint8_t>(cy, cx) != 0) continue;
        taken.at<std::uint8_t>(cy, cx) = 1;
        points.push_back(T_world_cam * Eigen::Vector3d((cx - camera_.cx) / camera_.f * z,
                                                       (cy - camera_.cy) / camera_.f * z, z));
      }
    }
  }
  cycles_.push_back(std::move(points));
  if (cycles_.size() > kMaxStoredCycles) cycles_.pop_front();
}

void SampleCeiling::Score(std::size_t cycles, const cv::Mat& gt_depth_m, const cv::Mat& gt_edges,
                          const geometry::RigidTransform& T_world_cam) {
  std::vector<Eigen::Vector3d> points;
  const std::size_t n = std::min(cycles, cycles_.size());
  for (std::size_t i = cycles_.size() - n; i < cycles_.size(); ++i)
    points.insert(points.end(), cycles_[i].begin(), cycles_[i].end());
  scored_.Add(points, gt_depth_m, gt_edges, T_world_cam);
}

}  // namespace aavio::eval
