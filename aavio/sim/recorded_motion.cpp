#include "aavio/sim/recorded_motion.hpp"

#include <cmath>

#include "aavio/common/format.hpp"

namespace aavio::sim {

Eigen::Matrix3d DrivingBodyToCamera(const std::vector<geometry::StampedPose>& poses) {
  Eigen::Vector3d travel = Eigen::Vector3d::Zero(), down = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i + 1 < poses.size(); ++i) {
    const Eigen::Matrix3d& R = poses[i].T_world_body.R;
    travel += R.transpose() * (poses[i + 1].T_world_body.t - poses[i].T_world_body.t);
    down += R.transpose() * Eigen::Vector3d(0, 0, -1);
  }
  const Eigen::Vector3d y = down.normalized();
  const Eigen::Vector3d z = (travel - travel.dot(y) * y).normalized();
  Eigen::Matrix3d R_body_cam;
  R_body_cam.col(0) = y.cross(z);
  R_body_cam.col(1) = y;
  R_body_cam.col(2) = z;
  return R_body_cam;
}

Expected<CameraPath> CameraPathFromRecording(const std::vector<geometry::StampedPose>& recorded,
                                             double start_s, double duration_s,
                                             const std::string& mode) {
  if (recorded.size() < 2) return InvalidArgument("a recorded path needs at least 2 poses");
  if (mode != "identity" && mode != "driving" && mode != "auto") {
    return InvalidArgument("body-to-camera must be identity, driving or auto, got '" + mode + "'");
  }
  const TimeNs start = recorded.front().t_ns + SecondsToNs(start_s);
  const TimeNs end = duration_s > 0.0 ? start + SecondsToNs(duration_s) : recorded.back().t_ns;
  std::vector<geometry::StampedPose> cropped;
  for (const geometry::StampedPose& p : recorded) {
    if (p.t_ns >= start && p.t_ns <= end) cropped.push_back(p);
  }
  if (cropped.size() < 2) {
    return InvalidArgument(
        StrFormat("the start and duration leave fewer than 2 poses (the path covers %.3f s)",
                  NsToSeconds(recorded.back().t_ns - recorded.front().t_ns)));
  }
  double length = 0.0;
  for (std::size_t i = 1; i < cropped.size(); ++i) {
    length += (cropped[i].T_world_body.t - cropped[i - 1].T_world_body.t).norm();
  }
  const double seconds = NsToSeconds(cropped.back().t_ns - cropped.front().t_ns);
  const bool vehicle = length > 20.0 && length / seconds > 2.0;
  CameraPath path;
  Eigen::Matrix3d R_body_cam = Eigen::Matrix3d::Identity();
  if (mode == "driving" || (mode == "auto" && vehicle)) {
    R_body_cam = DrivingBodyToCamera(cropped);
    path.body_to_camera = StrFormat("driving rule (body to camera rotation %.1f deg)",
                                    geometry::LogSO3(R_body_cam).norm() * 180.0 / M_PI);
  }
  const geometry::RigidTransform T_body_cam(R_body_cam, Eigen::Vector3d::Zero());
  const geometry::RigidTransform T_first = cropped.front().T_world_body * T_body_cam;
  const geometry::RigidTransform T_first_inv = T_first.Inverse();
  for (const geometry::StampedPose& p : cropped) {
    path.poses.push_back({p.t_ns, T_first_inv * (p.T_world_body * T_body_cam)});
  }
  path.gravity_world = T_first.R.transpose() * Eigen::Vector3d(0, 0, -9.81);
  return path;
}

}  // namespace aavio::sim
