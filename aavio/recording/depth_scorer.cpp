#include "aavio/recording/depth_scorer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "aavio/common/format.hpp"

namespace aavio::recording {

Expected<DepthScorer> DepthScorer::Create(const RunGroundTruth& truth,
                                          const std::vector<geometry::StampedPose>& gt_poses) {
  if (truth.depth_dir.empty())
    return InvalidArgument(truth.sequence + ": names no ground-truth depth (ground_truth.depth)");
  geometry::PoseBuffer poses(0);
  for (const geometry::StampedPose& p : gt_poses)
    AAVIO_RETURN_IF_ERROR(poses.Insert(p.t_ns, p.T_world_body));
  Expected<std::vector<io::GtDepthEntry>> frames = io::ReadGtDepthIndex(truth.depth_dir);
  if (!frames) return frames.status();
  return DepthScorer(truth, std::move(poses), std::move(*frames));
}

Expected<std::optional<DepthScorer::Frame>> DepthScorer::Nearest(TimeNs t_ns) const {
  auto it = std::lower_bound(frames_.begin(), frames_.end(), t_ns,
                             [](const io::GtDepthEntry& e, TimeNs t) { return e.t_ns < t; });
  const io::GtDepthEntry* best = nullptr;
  for (auto c : {it, it == frames_.begin() ? it : it - 1}) {
    if (c == frames_.end()) continue;
    if (!best || std::llabs(c->t_ns - t_ns) < std::llabs(best->t_ns - t_ns)) best = &*c;
  }
  if (!best || std::llabs(best->t_ns - t_ns) > kDepthMatchWindowNs) return std::optional<Frame>();
  Expected<geometry::RigidTransform> pose = poses_.Query(best->t_ns);
  if (!pose) return std::optional<Frame>();  // outside the ground truth's time range
  Expected<io::GtDepthFrame> frame =
      io::LoadGtDepthFrame(truth_.depth_dir, *best, truth_.fb, truth_.disparity_offset);
  if (!frame) return frame.status();
  return std::optional<Frame>(Frame{std::move(*frame), *pose});
}

Expected<bool> DepthScorer::AddInWorld(TimeNs t_ns,
                                       const std::vector<Eigen::Vector3d>& points_world) {
  Expected<std::optional<Frame>> nearest = Nearest(t_ns);
  if (!nearest) return nearest.status();
  if (!*nearest) return false;
  AddInWorld(**nearest, points_world);
  return true;
}

void DepthScorer::AddInWorld(const Frame& f, const std::vector<Eigen::Vector3d>& points_world) {
  accumulator_.Add(points_world, f.frame.depth_m, f.frame.edges, f.T_world_cam);
}

Expected<bool> DepthScorer::AddDepthImage(TimeNs t_ns, const cv::Mat& depth_m) {
  const eval::PinholeCamera& camera = truth_.camera;
  if (depth_m.type() != CV_32FC1 || depth_m.cols != camera.width || depth_m.rows != camera.height) {
    return InvalidArgument(StrFormat(
        "a depth map of %dx%d pixels, but the sequence's camera is %dx%d (is this a run of that "
        "sequence?)",
        depth_m.cols, depth_m.rows, camera.width, camera.height));
  }
  Expected<geometry::RigidTransform> T_world_map_cam = poses_.Query(t_ns);
  Expected<std::optional<Frame>> nearest = Nearest(t_ns);
  if (!nearest) return nearest.status();
  if (!*nearest || !T_world_map_cam) return false;
  const Frame& f = **nearest;
  // The map's points in its camera; that camera is the "world" of the accumulator, and the
  // ground-truth frame's camera sits at the true motion between the two stamps.
  std::vector<Eigen::Vector3d> points;
  for (int v = 0; v < depth_m.rows; ++v) {
    const float* row = depth_m.ptr<float>(v);
    for (int u = 0; u < depth_m.cols; ++u) {
      const double z = row[u];
      if (z > 0.0 && std::isfinite(z))
        points.emplace_back((u - camera.cx) / camera.f * z, (v - camera.cy) / camera.f * z, z);
    }
  }
  accumulator_.Add(points, f.frame.depth_m, f.frame.edges,
                   T_world_map_cam->Inverse() * f.T_world_cam);
  return true;
}

}  // namespace aavio::recording
