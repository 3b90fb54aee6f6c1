#include "aavio/sim/world.hpp"

#include "aavio/common/config_fields.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/sim/motions.hpp"
#include "aavio/sim/scene_builder.hpp"

namespace aavio::sim {
namespace {

Expected<CameraPath> BuildMotion(const SimulationRequest& request, const SimulationPreset& preset) {
  if (request.trajectory.empty()) {
    CameraPath motion;
    const double duration = request.duration_s.value_or(preset.duration_s);
    switch (preset.motion) {
      case MotionKind::kHandHeld:
        motion.poses = HandHeldMotion(duration, request.seed);
        break;
      case MotionKind::kDriving:
        motion.poses = DrivingMotion(duration, request.seed);
        break;
      case MotionKind::kDrone:
        motion.poses = DroneMotion(duration, request.seed);
        break;
    }
    motion.gravity_world = BuiltInGravity();
    return motion;
  }
  Expected<std::vector<geometry::StampedPose>> recorded = io::ReadTumTrajectory(request.trajectory);
  if (!recorded) return recorded.status();
  Expected<CameraPath> path = CameraPathFromRecording(
      *recorded, request.start_s, request.duration_s.value_or(0.0), request.body_to_camera);
  if (!path) return path.status().WithContext(request.trajectory);
  return path;
}

/// Rotation taking the canonical scene frame (y down, z forward) to the world: y along gravity,
/// z along the first camera's view projected onto the level plane.
geometry::RigidTransform SceneFrame(const CameraPath& motion) {
  const Eigen::Vector3d y = motion.gravity_world.normalized();
  // The first camera's view direction, levelled; a camera looking along gravity uses its image
  // "up" (−y) instead, then its x axis.
  const Eigen::Matrix3d& R0 = motion.poses.front().T_world_body.R;
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  for (const Eigen::Vector3d& candidate :
       {Eigen::Vector3d(R0.col(2)), Eigen::Vector3d(-R0.col(1)), Eigen::Vector3d(R0.col(0))}) {
    const Eigen::Vector3d level = candidate - candidate.dot(y) * y;
    if (level.norm() > 0.3) {
      z = level.normalized();
      break;
    }
  }
  Eigen::Matrix3d R;
  R.col(0) = y.cross(z);
  R.col(1) = y;
  R.col(2) = z;
  return {R, Eigen::Vector3d::Zero()};
}

}  // namespace

Status SimulationRequest::Validate() const {
  constexpr double kDay_s = 86400.0;
  FieldChecker check;
  if (duration_s) check.InRange("duration_s", *duration_s, 1e-3, kDay_s);
  check.InRange("start_s", start_s, 0.0, kDay_s * 365.0);
  check.Require(format == "h5" || format == "bag" || format == "txt", "format",
                "= '" + format + "' must be h5, bag or txt");
  return check.status();
}

geometry::RigidTransform SimulationWorld::T_world_camera(int side, TimeNs t_ns) const {
  const geometry::RigidTransform T_rect_left(rig.R_rect_left_left(), Eigen::Vector3d::Zero());
  const geometry::RigidTransform T_world_left = spline.Pose(t_ns) * T_rect_left;
  return side == 0 ? T_world_left : T_world_left * rig.T_right_left().Inverse();
}

Expected<SimulationWorld> BuildSimulationWorld(const SimulationRequest& request) {
  AAVIO_RETURN_IF_ERROR(request.Validate());
  Expected<SimulationPreset> preset = GetSimulationPreset(request.preset);
  if (!preset) return preset.status();
  Expected<SensorModel> sensor = MakeSensorModel(*preset, request.sensor, request.effects);
  if (!sensor) return sensor.status();
  preset->events = sensor->events;
  preset->imu = sensor->imu;
  Expected<geometry::StereoRig> rig = preset->rig();
  if (!request.calibration.empty()) {
    Expected<io::LoadedCalibration> loaded = io::LoadCalibration(request.calibration);
    if (!loaded) return loaded.status();
    rig = loaded->rig;
  }
  if (!rig) return rig.status();
  Expected<geometry::StereoRig> calibration_rig =
      PerturbCalibration(*rig, sensor->rig, request.seed);
  if (!calibration_rig) return calibration_rig.status();
  Expected<CameraPath> motion = BuildMotion(request, *preset);
  if (!motion) return motion.status();
  Expected<MotionSpline> spline = MotionSpline::Fit(motion->poses);
  if (!spline) return spline.status();

  const geometry::RigidTransform T_world_canonical = SceneFrame(*motion);
  Scene scene = BuildScene(preset->scene, motion->poses, motion->gravity_world,
                           preset->camera_height_m, request.seed);
  if (preset->scene != SceneKind::kStreet) scene.Transform(T_world_canonical);
  return SimulationWorld{
      std::move(*preset), std::move(*sensor), std::move(*rig),  std::move(*calibration_rig),
      std::move(*motion), std::move(*spline), std::move(scene), T_world_canonical};
}

}  // namespace aavio::sim
