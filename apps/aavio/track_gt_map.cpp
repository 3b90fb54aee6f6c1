// `aavio run --gt-map`: tracking alone against maps built from the sequence's ground truth,
// scored by the relative pose error over 100 ms against the ground-truth poses. A map holds the
// pixels mapping would reconstruct — the edge samples of the tick at a ground-truth depth frame —
// with their true depth, placed in the world with the true pose: the map of a perfect mapper.
// (All labelled edges would be a different map: most of them are textures that move along
// themselves and give no events, which tracking cannot register against.)
#include "track_gt_map.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "aavio/common/format.hpp"
#include "aavio/geometry/rotation.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/pipeline/stage_timings.hpp"
#include "aavio/pipeline/odometry.hpp"

namespace aavio::cli {
namespace {

namespace fs = std::filesystem;

// The map of one ground-truth depth frame: the tick's edge samples with their true depth.
Expected<std::shared_ptr<tracking::TrackingMap>> GroundTruthMap(
    const OpenedSequence& s, const io::GtDepthEntry& entry, const events::Observation& obs,
    const geometry::RigidTransform& T_world_cam) {
  const geometry::StereoRig& rig = s.calibration.rig;
  Expected<io::GtDepthFrame> frame =
      io::LoadGtDepthFrame(s.description.gt_depth, entry, rig.focal_px() * rig.baseline_m(),
                           rig.cx_left() - rig.cx_right());
  if (!frame) return frame.status();
  auto map = std::make_shared<tracking::TrackingMap>();
  map->T_world_ref = T_world_cam;
  for (const events::EdgeSample& sample : obs.samples) {
    const int u = static_cast<int>(std::lround(sample.u)), v = static_cast<int>(std::lround(sample.v));
    if (u < 0 || v < 0 || u >= frame->depth_m.cols || v >= frame->depth_m.rows) continue;
    const double z = frame->depth_m.at<float>(v, u);
    if (!(z > 0.0)) continue;
    const Eigen::Vector3d p((u - rig.cx_left()) / rig.focal_px() * z,
                            (v - rig.cy()) / rig.focal_px() * z, z);
    map->points_world.push_back(T_world_cam * p);
  }
  return map;
}

}  // namespace

Status RunTrackingOnGtMap(const RunRequest& request, Context& ctx) {
  const auto wall_start = std::chrono::steady_clock::now();
  OpenedSequence& s = *request.sequence;
  const geometry::PoseBuffer& gt = *request.gt_poses;
  if (s.description.gt_depth.empty()) {
    return InvalidArgument(s.description.origin +
                           ": --gt-map needs ground-truth depth "
                           "(ground_truth.depth in sequence.yaml)");
  }
  Expected<std::vector<io::GtDepthEntry>> index = io::ReadGtDepthIndex(s.description.gt_depth);
  if (!index) return index.status();
  Expected<geometry::RigidTransform> start_pose = gt.Query(request.begin_ns);
  if (!start_pose) return start_pose.status().WithContext("ground truth at the start");

  pipeline::Odometry front_end(s.calibration.rig, *request.config, request.begin_ns, *start_pose,
                               /*run_mapping=*/false);
  std::size_t next_map = 0;
  Status map_status = Status::Ok();
  front_end.before_tick = [&](const events::Observation& obs) {
    // A new map at the first tick at or after each ground-truth depth frame.
    const TimeNs t = obs.t_ns;
    std::size_t newest = next_map;
    while (newest < index->size() && (*index)[newest].t_ns <= t)
      ++newest;
    if (newest == next_map || !map_status.ok()) return;
    next_map = newest;
    const io::GtDepthEntry& entry = (*index)[newest - 1];
    Expected<geometry::RigidTransform> pose = gt.Query(t);
    if (!pose) return;
    Expected<std::shared_ptr<tracking::TrackingMap>> map = GroundTruthMap(s, entry, obs, *pose);
    if (!map) {
      map_status = map.status();
      return;
    }
    front_end.SetTrackingMap(std::move(*map));
  };
  std::vector<geometry::StampedPose> estimate, truth;
  pipeline::StageTimings timings;
  std::map<std::string, int> status_counts;
  front_end.on_tick = [&](const pipeline::OdometryTick& r) {
    timings.Add("time_surface", r.representation.time_surface_ms);
    timings.Add("tracking", r.tracking_ms - r.prediction_ms,
                static_cast<double>(r.registration_iterations));
    timings.Add("prediction", r.prediction_ms);
    status_counts[r.status == tracking::TrackingStatus::kOk     ? "ok"
                  : r.status == tracking::TrackingStatus::kLost ? "lost"
                                                                : "no_map"]++;
    Expected<geometry::RigidTransform> g = gt.Query(r.t_ns);
    if (!g) return;
    estimate.push_back({r.t_ns, r.T_world_cam});
    truth.push_back({r.t_ns, *g});
  };
  std::int64_t events = 0;
  io::SensorPacket packet;
  while (true) {
    Expected<bool> more = s.reader->Next(&packet);
    if (!more) return more.status();
    if (!*more || packet.t_begin_ns >= request.end_ns) break;
    events += static_cast<std::int64_t>(packet.left.size() + packet.right.size());
    AAVIO_RETURN_IF_ERROR(
        front_end.Process(packet.left, packet.right, packet.imu, packet.t_end_ns));
    AAVIO_RETURN_IF_ERROR(map_status);
  }
  // Relative pose error over 100 ms (10 ticks): rotation [deg] and translation [m].
  std::vector<double> rot_err, trans_err;
  for (std::size_t i = 0; i + 10 < estimate.size(); ++i) {
    const geometry::RigidTransform de =
        estimate[i].T_world_body.Inverse() * estimate[i + 10].T_world_body;
    const geometry::RigidTransform dg =
        truth[i].T_world_body.Inverse() * truth[i + 10].T_world_body;
    rot_err.push_back(geometry::LogSO3(dg.R.transpose() * de.R).norm() * 180.0 / M_PI);
    trans_err.push_back((de.t - dg.t).norm());
  }
  auto rmse = [](const std::vector<double>& v) {
    double s2 = 0.0;
    for (const double x : v)
      s2 += x * x;
    return v.empty() ? 0.0 : std::sqrt(s2 / static_cast<double>(v.size()));
  };
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double data_s =
      estimate.empty() ? 0.0 : NsToSeconds(estimate.back().t_ns - estimate.front().t_ns);
  std::error_code ec;
  fs::create_directories(request.out_dir, ec);
  if (ec) return IoError(request.out_dir + ": cannot create the folder (" + ec.message() + ")");
  AAVIO_RETURN_IF_ERROR(io::WriteTumTrajectory(
      (fs::path(request.out_dir) / "stamped_traj_estimate.txt").string(), estimate));
  nlohmann::json summary;
  summary["mode"] = "tracking_only_gt_map";
  summary["gyro_prior"] = request.config->imu.use_gyro_prior;
  summary["data_duration_s"] = data_s;
  summary["wall_s"] = wall_s;
  summary["events"] = events;
  summary["poses"] = estimate.size();
  summary["status"] = status_counts;
  summary["rpe_100ms"] = {{"rotation_deg_rmse", rmse(rot_err)},
                          {"translation_m_rmse", rmse(trans_err)},
                          {"pairs", rot_err.size()}};
  for (const auto& [stage, st] : timings.Summary()) {
    summary["stages"][stage] = {{"median_ms", st.median_ms},
                                {"p95_ms", st.p95_ms},
                                {"calls", st.calls},
                                {"median_items", st.median_items}};
  }
  AAVIO_RETURN_IF_ERROR(io::WriteTextFile((fs::path(request.out_dir) / "summary.json").string(),
                                          summary.dump(2) + "\n"));
  ctx.out << StrFormat(
      "tracked %.2f s against ground-truth maps (gyroscope prior %s): %zu poses, "
      "RPE over 100 ms: rotation %.4f deg, translation %.4f m (RMSE)\n",
      data_s, request.config->imu.use_gyro_prior ? "on" : "off", estimate.size(), rmse(rot_err),
      rmse(trans_err));
  ctx.out << "wrote " << request.out_dir << "/{stamped_traj_estimate.txt,summary.json}\n";
  return Status::Ok();
}

}  // namespace aavio::cli
