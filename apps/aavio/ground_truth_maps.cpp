#include "ground_truth_maps.hpp"

#include <cmath>

#include "aavio/geometry/rotation.hpp"

namespace aavio::cli {

Expected<GroundTruthMaps> GroundTruthMaps::Create(const OpenedSequence& s,
                                                  const geometry::PoseBuffer& gt_poses) {
  if (s.description.gt_depth.empty()) {
    return InvalidArgument(s.description.origin +
                           ": --gt-map needs ground-truth depth "
                           "(ground_truth.depth in sequence.yaml)");
  }
  Expected<std::vector<io::GtDepthEntry>> index = io::ReadGtDepthIndex(s.description.gt_depth);
  if (!index) return index.status();
  return GroundTruthMaps(s, gt_poses, std::move(*index));
}

Expected<std::shared_ptr<tracking::TrackingMap>> GroundTruthMaps::MapFor(
    const events::Observation& obs) {
  std::size_t newest = next_;
  while (newest < index_.size() && index_[newest].t_ns <= obs.t_ns)
    ++newest;
  if (newest == next_) return std::shared_ptr<tracking::TrackingMap>();
  next_ = newest;
  Expected<geometry::RigidTransform> T_world_cam = poses_->Query(obs.t_ns);
  if (!T_world_cam) return std::shared_ptr<tracking::TrackingMap>();
  const geometry::StereoRig& rig = sequence_->calibration.rig;
  Expected<io::GtDepthFrame> frame =
      io::LoadGtDepthFrame(sequence_->description.gt_depth, index_[newest - 1],
                           rig.focal_px() * rig.baseline_m(), rig.cx_left() - rig.cx_right());
  if (!frame) return frame.status();
  auto map = std::make_shared<tracking::TrackingMap>();
  map->T_world_ref = *T_world_cam;
  for (const events::EdgeSample& sample : obs.samples) {
    const int u = static_cast<int>(std::lround(sample.u)),
              v = static_cast<int>(std::lround(sample.v));
    if (u < 0 || v < 0 || u >= frame->depth_m.cols || v >= frame->depth_m.rows) continue;
    const double z = frame->depth_m.at<float>(v, u);
    if (!(z > 0.0)) continue;
    const Eigen::Vector3d p((u - rig.cx_left()) / rig.focal_px() * z,
                            (v - rig.cy()) / rig.focal_px() * z, z);
    map->points_world.push_back(*T_world_cam * p);
  }
  return map;
}

RelativeError100Ms RelativeErrorOver100Ms(const std::vector<geometry::StampedPose>& estimate,
                                          const geometry::PoseBuffer& gt_poses) {
  std::vector<geometry::StampedPose> est, truth;
  for (const geometry::StampedPose& p : estimate) {
    Expected<geometry::RigidTransform> g = gt_poses.Query(p.t_ns);
    if (!g) continue;
    est.push_back(p);
    truth.push_back({p.t_ns, *g});
  }
  double rot2 = 0.0, trans2 = 0.0;
  RelativeError100Ms e;
  for (std::size_t i = 0; i + 10 < est.size(); ++i) {
    const geometry::RigidTransform de = est[i].T_world_body.Inverse() * est[i + 10].T_world_body;
    const geometry::RigidTransform dg =
        truth[i].T_world_body.Inverse() * truth[i + 10].T_world_body;
    const double rot_deg = geometry::LogSO3(dg.R.transpose() * de.R).norm() * 180.0 / M_PI;
    rot2 += rot_deg * rot_deg;
    trans2 += (de.t - dg.t).squaredNorm();
    ++e.pairs;
  }
  if (e.pairs > 0) {
    e.rotation_deg_rmse = std::sqrt(rot2 / static_cast<double>(e.pairs));
    e.translation_m_rmse = std::sqrt(trans2 / static_cast<double>(e.pairs));
  }
  return e;
}

}  // namespace aavio::cli
