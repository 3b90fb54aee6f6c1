#include "aavio/sim/world.hpp"

#include <algorithm>
#include <cmath>

#include "aavio/common/config_fields.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/sim/motions.hpp"
#include "aavio/sim/scene_builder.hpp"

namespace aavio::sim {
namespace {

// The fast-motion and stop stretches as a warp of time: in a stretch of D seconds at factor K
// (0 for a stop) the motion runs at a speed that goes from 1 to K over its first quarter (a
// raised cosine), holds, and goes back over its last quarter, so speed and acceleration stay
// continuous (a shake or a braking, not a jump). Such a stretch covers D + (K − 1)·(3/4)·D
// seconds of the motion.
double Factor(const Disturbance& d) {
  return d.kind == Disturbance::Kind::kStop ? 0.0 : d.factor;
}

bool WarpsTime(const Disturbance& d) {
  return d.kind == Disturbance::Kind::kFastMotion || d.kind == Disturbance::Kind::kStop;
}

double Speed(const std::vector<Disturbance>& disturbances, double t_s) {
  double speed = 1.0;
  for (const Disturbance& d : disturbances) {
    if (!WarpsTime(d) || !d.Covers(t_s)) continue;
    const double ramp = 0.25 * d.duration_s;
    const double into = std::min(t_s - d.start_s, d.start_s + d.duration_s - t_s);
    const double w = into >= ramp ? 1.0 : 0.5 - 0.5 * std::cos(M_PI * into / ramp);
    speed += (Factor(d) - 1.0) * w;
  }
  return speed;
}

double ExtraMotionS(const std::vector<Disturbance>& disturbances) {
  double extra = 0.0;
  for (const Disturbance& d : disturbances) {
    if (!WarpsTime(d)) continue;
    if (d.start_s >= 0.0) {
      extra += (Factor(d) - 1.0) * 0.75 * d.duration_s;
      continue;
    }
    // A stretch begun before the start (the rest at the start): only its part from 0 counts.
    constexpr double kStep_s = 1e-4;
    for (double t = 0.5 * kStep_s; t < d.start_s + d.duration_s; t += kStep_s)
      extra += (Speed({d}, t) - 1.0) * kStep_s;
  }
  return extra;
}

// The disturbances that warp time, with the rest at the start as a stop whose standstill begins
// at 0: a stretch of 2·rest from −rest/2 (its slowing down lies before the start).
std::vector<Disturbance> TimeWarps(const SimulationRequest& request) {
  std::vector<Disturbance> warps = request.disturbances;
  if (request.rest_at_start_s > 0.0) {
    warps.push_back(
        {Disturbance::Kind::kStop, -0.5 * request.rest_at_start_s, 2.0 * request.rest_at_start_s});
  }
  return warps;
}

// Restamps the poses (stamps in motion time) to data time through the warp above: data time
// advances by dt while the motion advances by Speed·dt (integrated in 0.1 ms steps). A stop's
// standstill holds no pose of the motion, so it gets its own: the pose where the motion stops,
// every 50 ms of the standstill, which keeps the spline through the poses standing still.
void WarpTime(const std::vector<Disturbance>& disturbances,
              std::vector<geometry::StampedPose>* poses) {
  if (poses->empty() || std::none_of(disturbances.begin(), disturbances.end(), WarpsTime)) return;
  const TimeNs t0 = poses->front().t_ns;
  constexpr double kStep_s = 1e-4;
  struct Hold {
    double begin_s, end_s;   // data time, seconds from the start
    double motion_s = -1.0;  // motion time where it stands, once reached
  };
  std::vector<Hold> holds;
  for (const Disturbance& d : disturbances) {
    if (d.kind == Disturbance::Kind::kStop)
      holds.push_back({d.start_s + 0.25 * d.duration_s, d.start_s + 0.75 * d.duration_s});
  }
  const std::vector<geometry::StampedPose> motion = *poses;
  double t = 0.0, u = 0.0;  // data time and motion time, seconds from the start
  for (geometry::StampedPose& p : *poses) {
    const double target = NsToSeconds(p.t_ns - t0);
    while (u < target) {
      for (Hold& hold : holds) {
        if (hold.motion_s < 0.0 && t >= hold.begin_s) hold.motion_s = u;
      }
      const double du = Speed(disturbances, t) * kStep_s;
      if (u + du >= target) {
        t += (target - u) / du * kStep_s;
        u = target;
        break;
      }
      u += du;
      t += kStep_s;
    }
    p.t_ns = t0 + SecondsToNs(t);
  }
  constexpr double kHoldStep_s = 0.05;
  for (const Hold& hold : holds) {
    if (hold.motion_s < 0.0) continue;  // the motion ends before it
    const TimeNs u_ns = t0 + SecondsToNs(hold.motion_s);
    auto after =
        std::upper_bound(motion.begin(), motion.end(), u_ns,
                         [](TimeNs t_ns, const geometry::StampedPose& q) { return t_ns < q.t_ns; });
    if (after == motion.begin() || after == motion.end()) continue;
    const geometry::StampedPose& a = *(after - 1);
    const double alpha =
        static_cast<double>(u_ns - a.t_ns) / static_cast<double>(after->t_ns - a.t_ns);
    const geometry::RigidTransform T_stop =
        geometry::InterpolatePose(a.T_world_body, after->T_world_body, alpha);
    std::vector<geometry::StampedPose> standstill;
    for (double s = hold.begin_s; s <= hold.end_s; s += kHoldStep_s)
      standstill.push_back({t0 + SecondsToNs(s), T_stop});
    // The warped poses strictly inside the standstill (at most one, where the motion stops)
    // give way to it.
    std::erase_if(*poses, [&](const geometry::StampedPose& q) {
      return q.t_ns >= standstill.front().t_ns - SecondsToNs(0.5 * kHoldStep_s) &&
             q.t_ns <= standstill.back().t_ns + SecondsToNs(0.5 * kHoldStep_s);
    });
    poses->insert(
        std::upper_bound(poses->begin(), poses->end(), standstill.front().t_ns,
                         [](TimeNs t_ns, const geometry::StampedPose& q) { return t_ns < q.t_ns; }),
        standstill.begin(), standstill.end());
  }
}

// The motion of the preset or the recorded trajectory, `extra_s` seconds longer than asked, in
// the motion's own time (request.speed times data time).
Expected<CameraPath> FollowedMotion(const SimulationRequest& request,
                                    const SimulationPreset& preset, double extra_s) {
  const double speed = request.speed;
  if (request.trajectory.empty()) {
    CameraPath motion;
    const double duration = request.duration_s.value_or(preset.duration_s) * speed + extra_s;
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
      case MotionKind::kSinusoid:
        motion.poses = SinusoidMotion(duration, request.seed);
        break;
    }
    motion.gravity_world = BuiltInGravity();
    return motion;
  }
  Expected<std::vector<geometry::StampedPose>> recorded = io::ReadTumTrajectory(request.trajectory);
  if (!recorded) return recorded.status();
  Expected<CameraPath> path = CameraPathFromRecording(
      *recorded, request.start_s, request.duration_s ? *request.duration_s * speed + extra_s : 0.0,
      request.body_to_camera);
  if (!path) return path.status().WithContext(request.trajectory);
  return path;
}

// Restamps poses of the motion's own time to data time: t − t0 becomes (t − t0) / speed.
void ApplySpeed(double speed, std::vector<geometry::StampedPose>* poses) {
  if (speed == 1.0 || poses->empty()) return;
  const TimeNs t0 = poses->front().t_ns;
  for (geometry::StampedPose& p : *poses)
    p.t_ns = t0 + static_cast<TimeNs>(std::llround(static_cast<double>(p.t_ns - t0) / speed));
}

Expected<CameraPath> BuildMotion(const SimulationRequest& request, const SimulationPreset& preset) {
  const std::vector<Disturbance> warps = TimeWarps(request);
  Expected<CameraPath> path = FollowedMotion(request, preset, request.speed * ExtraMotionS(warps));
  if (path) ApplySpeed(request.speed, &path->poses);
  if (path) WarpTime(warps, &path->poses);
  if (path && path->poses.size() < 2) {
    return InvalidArgument(
        "disturbances: the stops leave no motion to follow; a stop must end within the sequence");
  }
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
  // The sequence's length: asked for, or the preset's when its own motion is followed (a
  // recorded trajectory's is known only once read).
  std::optional<double> length_s = duration_s;
  if (!length_s && trajectory.empty()) {
    if (Expected<SimulationPreset> p = GetSimulationPreset(preset); p.ok())
      length_s = p->duration_s;
  }
  check.InRange("speed", speed, 0.05, 10.0);
  check.InRange("rest_at_start_s", rest_at_start_s, 0.0, kDay_s);
  check.InRange("texture_contrast", texture_contrast, 0.2, 3.0);
  if (length_s && rest_at_start_s > 0.0)
    check.Require(1.5 * rest_at_start_s < *length_s, "rest_at_start_s",
                  "= " + FieldChecker::Num(rest_at_start_s) +
                      " s leaves the camera no time to move: it stands still for it and speeds "
                      "up over half of it, within the sequence's " +
                      FieldChecker::Num(*length_s) + " s (shorten it or lengthen --duration)");
  if (baseline_m) check.InRange("baseline_m", *baseline_m, 0.01, 2.0);
  if (!scene.empty() && !SceneKindNamed(scene).ok())
    check.Require(false, "scene", "= " + SceneKindNamed(scene).status().message());
  if (Status names = CheckWorldEffectNames(world_effects); !names.ok())
    check.Require(false, "world_effects", "= " + names.message());
  if (!motion.empty() && !MotionKindNamed(motion).ok())
    check.Require(false, "motion", "= " + MotionKindNamed(motion).status().message());
  check.Require(motion.empty() || trajectory.empty(), "motion",
                "and a trajectory cannot both be given: the camera follows one of them");
  check.InRange("start_s", start_s, 0.0, kDay_s * 365.0);
  check.Require(format == "h5" || format == "bag" || format == "txt", "format",
                "= '" + format + "' must be h5, bag or txt");
  for (const Disturbance& d : disturbances) {
    check.InRange("disturbances.start_s", d.start_s, 0.0, kDay_s);
    check.InRange("disturbances.duration_s", d.duration_s, 1e-3, kDay_s);
    if (d.kind == Disturbance::Kind::kFastMotion)
      check.InRange("disturbances.factor", d.factor, 1.0, 20.0);
    // A stop must end within the sequence (its motion resumes); any other stretch must at least
    // begin within it, or it would silently do nothing.
    if (d.kind == Disturbance::Kind::kStop && length_s)
      check.Require(d.start_s + d.duration_s <= *length_s, "disturbances",
                    "stop from " + FieldChecker::Num(d.start_s) + " s for " +
                        FieldChecker::Num(d.duration_s) + " s ends after the sequence (" +
                        FieldChecker::Num(*length_s) +
                        " s): a stop must end within it (lengthen --duration or shorten it)");
    if (d.kind != Disturbance::Kind::kStop && length_s)
      check.Require(d.start_s < *length_s, "disturbances",
                    "a stretch from " + FieldChecker::Num(d.start_s) +
                        " s starts after the sequence ends (" + FieldChecker::Num(*length_s) +
                        " s) and would change nothing: start it earlier or lengthen --duration");
  }
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
  if (!request.scene.empty()) preset->scene = *SceneKindNamed(request.scene);
  if (!request.motion.empty()) preset->motion = *MotionKindNamed(request.motion);
  Expected<geometry::StereoRig> rig = preset->rig();
  if (!request.calibration.empty()) {
    Expected<io::LoadedCalibration> loaded = io::LoadCalibration(request.calibration);
    if (!loaded) return loaded.status();
    rig = loaded->rig;
  }
  if (!rig) return rig.status();
  if (request.baseline_m) rig = rig->WithBaseline(*request.baseline_m);
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
  if (request.texture_contrast != 1.0) scene.ScaleContrast(request.texture_contrast);
  const geometry::CameraIntrinsics& K = rig->left().intrinsics();
  const WorldEffectPlacement placement{motion->poses, motion->gravity_world,
                                       std::atan(0.5 * K.width / K.fx),
                                       preset->scene == SceneKind::kStreet, request.seed};
  const WorldEffectsAdded added = AddWorldEffects(request.world_effects, placement, &scene);
  return SimulationWorld{
      std::move(*preset), std::move(*sensor), std::move(*rig),  std::move(*calibration_rig),
      std::move(*motion), std::move(*spline), std::move(scene), added,
      T_world_canonical};
}

}  // namespace aavio::sim
