#include "aavio/sim/recorded_motion.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "aavio/common/format.hpp"
#include "aavio/sim/path_smoothing.hpp"

namespace aavio::sim {

namespace {
constexpr double kSmoothingMargin_s = 2.0;
}  // namespace

Eigen::Matrix3d DrivingBodyToCamera(const std::vector<geometry::StampedPose>& poses) {
  // Forward: the mean direction of travel, in the body frame (robust: the car moves forward).
  Eigen::Vector3d forward = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const geometry::StampedPose& p : poses)
    mean += p.T_world_body.t;
  mean /= static_cast<double>(poses.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d d = poses[i].T_world_body.t - mean;
    scatter += d * d.transpose();
    if (i + 1 < poses.size()) {
      forward += poses[i].T_world_body.R.transpose() *
                 (poses[i + 1].T_world_body.t - poses[i].T_world_body.t);
    }
  }
  forward.normalize();
  // Vertical axis: the normal of the (nearly level) plane of the path when the path spans one;
  // for a nearly straight path the plane is undetermined and the body's own axis closest to
  // vertical is kept (the body's y axis, as camera-like body frames have it).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  Eigen::Vector3d vertical = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d spread = eigen.eigenvalues();  // ascending
  // The normal is well determined when the path spreads clearly more across (middle
  // eigenvalue) than out of its plane (smallest): a singular-value ratio above 5.
  if (spread(1) > 25.0 * spread(0)) {
    const Eigen::Vector3d normal_world = eigen.eigenvectors().col(0);
    vertical = Eigen::Vector3d::Zero();
    for (const geometry::StampedPose& p : poses)
      vertical += p.T_world_body.R.transpose() * normal_world;
  }
  Eigen::Vector3d down = (vertical - vertical.dot(forward) * forward).normalized();
  // Up or down cannot be told from positions (a left turn seen from above is a right turn seen
  // from below). Convention: the sign that keeps the camera's y axis on the side of the body's
  // y axis. The simulator lays the ground on the same side it gives the camera, so a twin is
  // self-consistent either way; at worst its turns are mirrored.
  if (down.y() < 0.0) down = -down;
  Eigen::Matrix3d R_body_cam;
  R_body_cam.col(1) = down;
  R_body_cam.col(2) = forward;
  R_body_cam.col(0) = down.cross(forward);
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
  // The measurement noise is removed over the crop and a margin, so that the crop's ends are
  // smoothed like its middle.
  const TimeNs margin = SecondsToNs(kSmoothingMargin_s);
  std::vector<geometry::StampedPose> around;
  for (const geometry::StampedPose& p : recorded) {
    if (p.t_ns >= start - margin && p.t_ns <= end + margin) around.push_back(p);
  }
  Expected<SmoothedPath> smoothed = SmoothRecordedPath(around);
  if (!smoothed) return smoothed.status();
  std::vector<geometry::StampedPose> cropped;
  for (const geometry::StampedPose& p : smoothed->poses) {
    if (p.t_ns >= start && p.t_ns <= end) cropped.push_back(p);
  }
  if (cropped.size() < 2) {
    return InvalidArgument(
        StrFormat("the start and duration leave fewer than 2 poses (the path covers %.3f s)",
                  NsToSeconds(recorded.back().t_ns - recorded.front().t_ns)));
  }
  // Whether it is a vehicle, and how its camera sits, is decided on the whole recording: a short
  // crop (or a stop) says little about either.
  double length = 0.0;
  for (std::size_t i = 1; i < recorded.size(); ++i) {
    length += (recorded[i].T_world_body.t - recorded[i - 1].T_world_body.t).norm();
  }
  const double seconds = NsToSeconds(recorded.back().t_ns - recorded.front().t_ns);
  const bool vehicle = length > 20.0 && length / seconds > 2.0;
  CameraPath path;
  path.smoothing = StrFormat(
      "measurement noise %.2f mm, %.3f deg rms removed (residual %.2f mm, %.3f deg)",
      1e3 * smoothed->noise.position_m, smoothed->noise.rotation_rad * 180.0 / M_PI,
      1e3 * smoothed->position_residual_m, smoothed->rotation_residual_rad * 180.0 / M_PI);
  Eigen::Matrix3d R_body_cam = Eigen::Matrix3d::Identity();
  if (mode == "driving" || (mode == "auto" && vehicle)) {
    R_body_cam = DrivingBodyToCamera(recorded);
    path.body_to_camera = StrFormat("driving rule (body to camera rotation %.1f deg)",
                                    geometry::LogSO3(R_body_cam).norm() * 180.0 / M_PI);
  }
  const geometry::RigidTransform T_body_cam(R_body_cam, Eigen::Vector3d::Zero());
  const geometry::RigidTransform T_first = cropped.front().T_world_body * T_body_cam;
  const geometry::RigidTransform T_first_inv = T_first.Inverse();
  for (const geometry::StampedPose& p : cropped) {
    path.poses.push_back({p.t_ns, T_first_inv * (p.T_world_body * T_body_cam)});
  }
  // Gravity along the first camera's +y: the driving rule put the ground there, and a hand-held
  // camera starts upright (recorded worlds need not be gravity-aligned: the ESVO2 ground-truth
  // worlds start at the first pose).
  path.gravity_world = 9.81 * Eigen::Vector3d::UnitY();
  return path;
}

}  // namespace aavio::sim
