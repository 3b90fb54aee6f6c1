#include "aavio/recording/run_recorder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/io/output_folder.hpp"
#include "aavio/io/ply.hpp"
#include "aavio/io/trajectory_io.hpp"

namespace aavio::recording {
namespace {

// summary.json "world": the frame the trajectory and map.ply are in.
nlohmann::json WorldJson(RunRecorderOptions::World world,
                         const std::optional<Eigen::Matrix3d>& R_gravity_first) {
  if (world == RunRecorderOptions::World::kGroundTruth) return {{"frame", "ground_truth"}};
  if (!R_gravity_first) {
    nlohmann::json j = {{"frame", "first_camera"}};
    if (world == RunRecorderOptions::World::kGravity) {
      j["gravity_unavailable"] =
          "no gravity was measured (it needs an IMU, its extrinsic and 2 s of tracked poses)";
    }
    return j;
  }
  const Eigen::Quaterniond q(*R_gravity_first);
  return {{"frame", "gravity"}, {"q_world_first_camera_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

// timings.csv's IMU columns: the gyroscope bias the tick used [rad/s], and with the IMU back-end
// (imu.mode=full, once solved) its accelerometer bias [m/s²] and gravity in the world [m/s²].
std::string ImuColumns(const pipeline::OdometryTick& t) {
  std::string out = StrFormat("%.6g,%.6g,%.6g", t.gyro_bias.x(), t.gyro_bias.y(), t.gyro_bias.z());
  if (!t.imu_state) return out + ",,,,,,";
  const imu::ImuState& s = *t.imu_state;
  return out + StrFormat(",%.6g,%.6g,%.6g,%.6g,%.6g,%.6g", s.accel_bias.x(), s.accel_bias.y(),
                         s.accel_bias.z(), s.gravity_world.x(), s.gravity_world.y(),
                         s.gravity_world.z());
}

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Resident set size now and at its peak [MB] (Linux /proc; 0 elsewhere).
std::pair<double, double> MemoryMb() {
  std::ifstream in("/proc/self/status");
  std::string key;
  double rss = 0.0, peak = 0.0, kb = 0.0;
  while (in >> key) {
    if (key == "VmRSS:" && in >> kb) rss = kb / 1024.0;
    if (key == "VmHWM:" && in >> kb) peak = kb / 1024.0;
  }
  return {rss, peak};
}

// What a run writes into its folder.
constexpr const char* kRunOutputs[] = {
    run_files::kTrajectory, run_files::kTrajectoryPart, run_files::kSummary,
    run_files::kTimings,    run_files::kConfig,         run_files::kCloud,
    run_files::kCloudPart,  run_files::kDepthDir,       run_files::kReserve};

// What Finish needs on a full disk: the trajectory (about 100 bytes a pose) and the cloud's
// vertices still buffered, config.yaml and summary.json.
constexpr std::uint64_t kReserveBytes = 16ull << 20;

}  // namespace

RunRecorder::RunRecorder(RunRecorderOptions options, const geometry::StereoRig& rig,
                         const pipeline::OdometryConfig& config, io::DepthFolderWriter depth_writer,
                         io::PlyWriter cloud_file, io::DiskReserve reserve)
    : options_(std::move(options)),
      config_(config),
      stereo_(mapping::RectifiedStereo::FromRig(rig)),
      T_imu_cam_(rig.T_imu_rect_left()),
      wall_start_(Clock::now()),
      depth_writer_(std::move(depth_writer)),
      // Every `depth_every_` confirmed maps (5 per second at the presets' 20 Hz) one goes to
      // depth/.
      depth_every_(std::max(1, static_cast<int>(std::lround(config.mapping.rate_hz / 5.0)))),
      // map.ply: points up to the far end of the depth range (at most 50 m) on voxels of 0.5 % of
      // it (rpg 0.5–5 m: 2.5 cm; DSEC: 25 cm).
      cloud_depth_m_(std::min(1.0 / config.mapping.inv_depth_min, 50.0)),
      cloud_(0.005 * cloud_depth_m_),
      cloud_file_(std::move(cloud_file)),
      reserve_(std::move(reserve)),
      colours_(config.mapping.inv_depth_min, config.mapping.inv_depth_max),
      event_gaps_(options_.begin_ns) {}

Expected<std::unique_ptr<RunRecorder>> RunRecorder::Open(RunRecorderOptions options,
                                                         const geometry::StereoRig& rig,
                                                         const pipeline::OdometryConfig& config) {
  const fs::path out(options.out_dir);
  AAVIO_RETURN_IF_ERROR(io::PrepareOutputFolder(
      options.out_dir, {.outputs = kRunOutputs, .overwrite = options.overwrite}));
  Expected<io::DepthFolderWriter> depth =
      io::DepthFolderWriter::Create((out / run_files::kDepthDir).string());
  if (!depth) return depth.status();
  Expected<io::PlyWriter> cloud = io::PlyWriter::Open((out / run_files::kCloud).string(),
                                                      "aavio global map (world frame, metres)");
  if (!cloud) return cloud.status();
  Expected<io::DiskReserve> reserve =
      io::DiskReserve::Create((out / run_files::kReserve).string(), kReserveBytes);
  if (!reserve) return reserve.status();
  std::unique_ptr<RunRecorder> recorder(new RunRecorder(
      std::move(options), rig, config, std::move(*depth), std::move(*cloud), std::move(*reserve)));
  const fs::path part = out / run_files::kTrajectoryPart;
  recorder->trajectory_file_.open(part, std::ios::binary | std::ios::trunc);
  recorder->trajectory_file_ << io::kTumHeader;
  if (!recorder->trajectory_file_) return IoError(part.string() + ": cannot write");
  return recorder;
}

Status RunRecorder::SetGroundTruth(const RunGroundTruth& truth,
                                   std::vector<geometry::StampedPose> gt_poses) {
  truth_ = truth;
  gt_poses_ = std::move(gt_poses);
  if (truth.depth_dir.empty()) return Status::Ok();
  Expected<DepthScorer> scorer = DepthScorer::Create(truth, gt_poses_);
  if (!scorer) return scorer.status();
  scorer_.emplace(std::move(*scorer));
  const eval::PinholeCamera& c = truth.camera;
  // What the map could cover at best: its cycles' samples at their true depth (runs on
  // ground-truth poses).
  ceiling_.emplace(eval::PinholeCamera{c.width, c.height, c.f, c.cx, c.cy},
                   1.0 / config_.mapping.inv_depth_max, 1.0 / config_.mapping.inv_depth_min,
                   config_.mapping.fusion.radius == 0 ? 2 : 3);
  return Status::Ok();
}

void RunRecorder::AddPacket(std::size_t events, double reading_ms) {
  events_ += static_cast<std::int64_t>(events);
  events_since_tick_ += static_cast<std::int64_t>(events);
  timings_.Add("event_reading", reading_ms, static_cast<double>(events));
}

void RunRecorder::AddRepresentation(TimeNs t_ns, const events::RepresentationTimings& t) {
  ++ticks_;
  timings_.Add("time_surface", t.time_surface_ms);
  timings_.Add("ts_derived", t.derived_ms);
  if (t.edges) {  // mapping ticks only
    timings_.Add("aa_map", t.aa_ms);
    timings_.Add("sampling", t.sampling_ms);
  }
  // Every 100 ticks: [data s, resident MB, wall s], for memory growth and slowdown over a run.
  if (ticks_ % 100 == 0) {
    over_time_.push_back({NsToSeconds(t_ns - options_.begin_ns), MemoryMb().first,
                          std::chrono::duration<double>(Clock::now() - wall_start_).count()});
  }
}

void RunRecorder::AddCycleReport(const mapping::MappingCycleReport& r) {
  mapping_counts_.Add(r);
  timings_.Add("matching", r.matching_ms, r.static_candidates + r.temporal_candidates);
  timings_.Add("depth_refinement", r.refinement_ms, r.static_matches + r.temporal_matches);
  timings_.Add("fusion", r.fusion_ms, r.map_points);
  timings_.Add("mapping_total", r.total_ms, r.samples);
}

Status RunRecorder::AddConfirmedMap(const mapping::LocalMap& map,
                                    const events::Observation* observation, bool score_written) {
  std::vector<mapping::CloudPoint> added;
  cloud_.Add(map, cloud_depth_m_, &added);
  std::vector<Eigen::Vector3f> points;
  std::vector<io::Rgb> rgb;
  for (const mapping::CloudPoint& p : added) {
    const cv::Vec3b c = colours_(static_cast<double>(p.inv_depth));
    points.push_back(p.p_world);
    rgb.push_back({c[2], c[1], c[0]});
  }
  AAVIO_RETURN_IF_ERROR(cloud_file_.Append(points, rgb));
  ++confirmed_maps_;
  confirmed_points_ += map.points.size();
  if ((confirmed_maps_ - 1) % depth_every_ != 0) return Status::Ok();
  const cv::Mat disparity = DisparityImage(map, stereo_);
  Expected<std::string> index =
      depth_writer_.Add(map.t_ns, disparity,
                        InverseDepthPicture(map, stereo_.width, stereo_.height, colours_,
                                            observation ? observation->ts_left : cv::Mat()));
  if (!index) return index.status();
  if (!score_written || !scorer_) return Status::Ok();
  // Scored as `aavio eval --run` scores the file: the same disparities, turned into depth.
  const auto start = Clock::now();
  Expected<bool> scored = scorer_->AddDepthImage(
      map.t_ns, io::DepthFromDisparityImage(disparity, truth_->fb, truth_->disparity_offset));
  evaluation_ms_ += MsSince(start);
  return scored.status();
}

Status RunRecorder::AddTick(const pipeline::OdometryTick& t) {
  AddRepresentation(t.t_ns, t.representation);
  trajectory_.push_back({t.t_ns, t.T_world_cam});
  trajectory_file_ << io::FormatTumPose(trajectory_.back());
  if (t.gap_before) event_gaps_.AddSkipped(t.gap_before->from_ns, t.gap_before->to_ns);
  event_gaps_.Add(t.t_ns, t.new_events_left, t.new_events_right);
  dropped_events_ = t.dropped_events;
  status_counts_[tracking::TrackingStatusName(t.status)]++;
  if (t.status == tracking::TrackingStatus::kLost)
    lost_reasons_[tracking::LostReasonName(t.lost_reason)]++;
  if (t.registration_stop)
    registration_stops_[tracking::RegistrationStopName(*t.registration_stop)]++;
  if (t.status == tracking::TrackingStatus::kImuOnly) {
    // Stretches carried on the IMU alone, [first tick, last tick] in data seconds.
    const double at = NsToSeconds(t.t_ns - options_.begin_ns);
    if (imu_only_.empty() || !previous_imu_only_) imu_only_.push_back({at, at});
    imu_only_.back()[1] = at;
  }
  previous_imu_only_ = t.status == tracking::TrackingStatus::kImuOnly;
  if (t.status != tracking::TrackingStatus::kNoMap) {
    timings_.Add("tracking", t.tracking_ms, t.registration_iterations);
    timings_.Add("prediction", t.prediction_ms);
  }
  if (t.mapping_wait_ms > 0.0) timings_.Add("mapping_wait", t.mapping_wait_ms);
  bootstraps_ += t.bootstrap;
  if (t.bootstrap && !first_bootstrap_ns_) first_bootstrap_ns_ = t.t_ns;
  if (!t.bootstrap_failure.empty()) {
    ++bootstrap_failures_;
    last_bootstrap_failure_ = t.bootstrap_failure;
  }
  skipped_cycles_ += t.mapping_skipped;
  reinitialisations_ += t.reinitialised;
  mapping_cycles_ += t.mapped ? 1 : 0;
  double mapping_ms = 0.0;
  if (t.mapped && !t.bootstrap) {
    AddCycleReport(t.mapping);
    mapping_ms = t.mapping.total_ms;
  }
  if (t.map && t.map->confirmed)  // provisional maps are for tracking only
    AAVIO_RETURN_IF_ERROR(AddConfirmedMap(*t.map, t.map_observation.get(), /*score_written=*/true));
  if (!csv_.is_open()) {
    csv_.open(fs::path(options_.out_dir) / run_files::kTimings);
    csv_ << "t_s,status,time_surface_ms,aa_ms,sampling_ms,tracking_ms,iterations,mapping_ms,"
            "map_points,lost_reason,events,gyro_bias_x,gyro_bias_y,gyro_bias_z,accel_bias_x,"
            "accel_bias_y,accel_bias_z,gravity_x,gravity_y,gravity_z\n";
  }
  csv_ << StrFormat(
      "%.6f,%s,%.4f,%.4f,%.4f,%.4f,%d,%.4f,%zu,%s,%lld,%s\n", NsToSeconds(t.t_ns),
      tracking::TrackingStatusName(t.status), t.representation.time_surface_ms,
      t.representation.aa_ms, t.representation.sampling_ms, t.tracking_ms,
      t.registration_iterations, mapping_ms, t.map ? t.map->points.size() : 0,
      t.status == tracking::TrackingStatus::kLost ? tracking::LostReasonName(t.lost_reason) : "",
      static_cast<long long>(events_since_tick_), ImuColumns(t).c_str());
  events_since_tick_ = 0;
  if (!csv_) return IoError(options_.out_dir + "/timings.csv: write failed (disk full?)");
  if (!trajectory_file_) {
    return IoError(options_.out_dir + "/" + run_files::kTrajectoryPart +
                   ": write failed (disk full?)");
  }
  return Status::Ok();
}

void RunRecorder::AddMappingTick(TimeNs t_ns, const events::RepresentationTimings& timings) {
  AddRepresentation(t_ns, timings);
}

Status RunRecorder::AddMappingCycle(const pipeline::MappingCycle& cycle) {
  ++mapping_cycles_;
  ++mapping_cycles_on_ground_truth_;
  bootstraps_ += cycle.bootstrap ? 1 : 0;
  if (!cycle.bootstrap) AddCycleReport(cycle.report);
  const bool confirmed = cycle.map && cycle.map->confirmed;
  if (confirmed)
    AAVIO_RETURN_IF_ERROR(
        AddConfirmedMap(*cycle.map, cycle.observation.get(), /*score_written=*/false));
  // Only cycles whose samples went into the fusion count for the ceiling.
  const bool fused = cycle.bootstrap || cycle.report.fused_cycles > 0;
  if (!fused || !scorer_) return Status::Ok();
  const auto start = Clock::now();
  Expected<std::optional<DepthScorer::Frame>> nearest = scorer_->Nearest(cycle.t_ns);
  if (!nearest) return nearest.status();
  if (*nearest) {
    const DepthScorer::Frame& f = **nearest;
    // The samples as a mapping cycle takes them (an SGM bootstrap uses all of the observation's;
    // its one cycle is counted with these), read on the ground-truth frame nearest the cycle.
    if (cycle.bootstrap) ceiling_->Clear();
    std::vector<Eigen::Vector2f> samples;
    for (const events::EdgeSample& e :
         mapping::MappingSamples(*cycle.observation, stereo_, config_.mapping))
      samples.emplace_back(e.u, e.v);
    ceiling_->AddCycle(samples, f.frame.depth_m, f.T_world_cam);
    if (confirmed) {
      scorer_->AddInWorld(f, cycle.map->points_world);
      ceiling_->Score(cycle.bootstrap ? 1 : static_cast<std::size_t>(cycle.report.fused_cycles),
                      f.frame.depth_m, f.frame.edges, f.T_world_cam);
    }
  }
  evaluation_ms_ += MsSince(start);
  return Status::Ok();
}

Status RunRecorder::CloseTrajectory(bool rewrite) {
  const fs::path out(options_.out_dir);
  const fs::path part = out / run_files::kTrajectoryPart;
  const fs::path path = out / run_files::kTrajectory;
  trajectory_file_.close();
  std::error_code ec;
  if (trajectory_.empty()) {  // no tick: no trajectory file
    fs::remove(part, ec);
    return Status::Ok();
  }
  if (trajectory_file_ && !rewrite) {
    fs::rename(part, path, ec);
    if (!ec) return Status::Ok();
  }
  // A write failed on the way (a full disk), or the world turned: written again whole, in the
  // part file's place.
  fs::remove(part, ec);
  return io::WriteTumTrajectory(path.string(), trajectory_);
}

// The velocity at every pose, and the trajectory in the layout and at the stamps asked for;
// their summary for summary.json.
nlohmann::json RunRecorder::WriteMotion(const std::optional<imu::GravityDirection>& gravity,
                                        const Eigen::Matrix3d& R_out_first,
                                        std::vector<Status>* failures) {
  auto keep = [failures](Status status) {
    if (!status.ok()) failures->push_back(std::move(status));
  };
  nlohmann::json j = nlohmann::json::object();
  if (trajectory_.empty()) return j;
  const fs::path out(options_.out_dir);
  const std::vector<geometry::StampedVelocity> velocities =
      geometry::EstimateVelocities(trajectory_, geometry::kDefaultVelocityHalfWindowNs);
  keep(io::WriteTextFile((out / run_files::kVelocity).string(), io::FormatVelocities(velocities)));
  std::vector<double> speeds, turn_rates;
  for (const geometry::StampedVelocity& v : velocities) {
    if (!v.valid) continue;
    speeds.push_back(v.v_body_mps.norm());
    turn_rates.push_back(v.w_body_radps.norm() * 180.0 / M_PI);
  }
  if (!speeds.empty()) {
    auto median = [](std::vector<double> x) {
      std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2), x.end());
      return x[x.size() / 2];
    };
    j["speed_median_mps"] = median(speeds);
    j["speed_max_mps"] = *std::max_element(speeds.begin(), speeds.end());
    j["turn_rate_median_dps"] = median(turn_rates);
  }
  if (gravity) {
    // In the world the files are in (z up already in a gravity world: q_up_world the identity).
    imu::GravityDirection g = *gravity;
    g.down_world = R_out_first * g.down_world;
    const Eigen::Quaterniond q(g.R_up_world());
    j["gravity"] = {{"down_world", {g.down_world.x(), g.down_world.y(), g.down_world.z()}},
                    {"magnitude_m_s2", g.magnitude_m_s2},
                    {"span_s", g.span_s},
                    {"q_up_world_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
  }
  if (options_.format == io::TrajectoryFormat::kTum && options_.poses_at.empty()) return j;
  const fs::path path = out / io::TrajectoryFileName(options_.format);
  if (options_.poses_at.empty()) {
    keep(io::WriteTrajectory(path.string(), trajectory_, velocities, options_.format));
    return j;
  }
  const geometry::Sampled sampled = geometry::SampleAt(trajectory_, velocities, options_.poses_at);
  keep(io::WriteTrajectory(path.string(), sampled.poses, sampled.velocities, options_.format));
  j["poses_at"] = {{"requested", options_.poses_at.size()},
                   {"written", sampled.poses.size()},
                   {"missing", sampled.missing.size()},
                   {"file", path.filename().string()}};
  if (!sampled.missing.empty()) {
    j["poses_at"]["first_missing_s"] = NsToSeconds(sampled.missing.front());
    j["poses_at"]["last_missing_s"] = NsToSeconds(sampled.missing.back());
  }
  return j;
}

Expected<RunRecord> RunRecorder::Finish(bool interrupted, TimeNs end_ns,
                                        const nlohmann::json& extra) {
  RunRecord record;
  record.wall_s = std::chrono::duration<double>(Clock::now() - wall_start_).count();
  record.data_s = NsToSeconds(std::max(end_ns, options_.begin_ns) - options_.begin_ns);
  const fs::path out(options_.out_dir);
  // Every file that can be written is, whatever failed before it (a full disk: the space held
  // back is given to these last files); the failures are listed in the summary.
  reserve_.reset();
  std::vector<Status> failures;
  auto keep = [&failures](Status status) {
    if (!status.ok()) failures.push_back(std::move(status));
  };
  if (csv_.is_open()) {
    csv_.close();
    if (!csv_) keep(IoError((out / run_files::kTimings).string() + ": write failed (disk full?)"));
  }
  // Gravity, measured in the first camera's world; with World::kGravity the files are turned z-up.
  std::optional<imu::GravityDirection> gravity;
  if (T_imu_cam_) gravity = gravity_.Estimate(trajectory_, T_imu_cam_->R);
  std::optional<Eigen::Matrix3d> R_out_first;
  if (options_.world == RunRecorderOptions::World::kGravity && gravity) {
    R_out_first = gravity->R_up_world();
    for (geometry::StampedPose& p : trajectory_)
      p.T_world_body =
          geometry::RigidTransform(*R_out_first, Eigen::Vector3d::Zero()) * p.T_world_body;
  }
  keep(CloseTrajectory(/*rewrite=*/R_out_first.has_value()));
  nlohmann::json motion =
      WriteMotion(gravity, R_out_first.value_or(Eigen::Matrix3d::Identity()), &failures);
  keep(io::WriteTextFile((out / run_files::kConfig).string(), options_.config_yaml));
  keep(cloud_file_.Close(R_out_first));
  keep(depth_writer_.Finish());

  // Accuracy against the ground truth (what `aavio eval --run` computes, se3-aligned); why there
  // is none goes into the summary (accuracy_error), which is written all the same.
  if (truth_ && !trajectory_.empty()) {
    Expected<TrajectoryEvaluation> e = EvaluateTrajectories(trajectory_, gt_poses_, {});
    if (e) {
      record.accuracy = std::move(*e);
    } else {
      record.accuracy_error = e.status().WithContext(truth_->trajectory_name());
    }
  }
  if (scorer_) {
    eval::DepthErrorSummary depth = scorer_->accumulator().Summary();
    if (depth.frames > 0) record.depth = std::move(depth);
  }
  // The ceiling is scored on the cycles of a run on ground-truth poses only.
  if (ceiling_ && mapping_cycles_on_ground_truth_ > 0) record.sample_ceiling = ceiling_->Summary();

  const double evaluation_s = evaluation_ms_ / 1e3;
  const double processing_s = std::max(record.wall_s - evaluation_s, 0.0);
  nlohmann::json& s = record.summary;
  s["mode"] = options_.mode;
  s["world"] = WorldJson(options_.world, R_out_first);
  s["version"] = options_.version;
  s["sequence"] = options_.sequence;
  s["calibration"] = options_.calibration;
  s["motion"] = motion;
  s["interrupted"] = interrupted;
  s["data_duration_s"] = record.data_s;
  s["wall_s"] = record.wall_s;
  s["evaluation_s"] = evaluation_s;
  s["real_time_factor"] = processing_s > 0.0 ? record.data_s / processing_s : 0.0;
  s["events"] = events_;
  s["dropped_events"] = dropped_events_;
  s["poses"] = trajectory_.size();
  s["status"] = status_counts_;
  s["lost_reasons"] = lost_reasons_;
  s["registration_stops"] = registration_stops_;
  event_gaps_.Finish(std::max(end_ns, options_.begin_ns));
  s["event_gaps"] = event_gaps_.Json();
  s["imu_only"] = nlohmann::json::array();
  for (const auto& [from, to] : imu_only_)
    s["imu_only"].push_back({from, to});
  s["bootstraps"] = bootstraps_;
  s["reinitialisations"] = reinitialisations_;
  // Ticks on which a (re-)initialisation found too few points, and the last one's reason.
  s["bootstrap_failures"] = {{"ticks", bootstrap_failures_},
                             {"last_reason", last_bootstrap_failure_}};
  // Data time from the first tick to the first map (null: never mapped; odometry runs only).
  s["first_bootstrap_s"] = nullptr;
  if (first_bootstrap_ns_ && !trajectory_.empty())
    s["first_bootstrap_s"] = NsToSeconds(*first_bootstrap_ns_ - trajectory_.front().t_ns);
  s["real_time_mode"] = config_.pipeline.real_time;
  s["mapping_cycles"] = mapping_cycles_;
  s["mapping_cycles_skipped"] = skipped_cycles_;
  s["mapping_per_cycle"] = mapping_counts_.PerCycleJson(mapping_cycles_);
  s["depth_maps"] = confirmed_maps_;
  s["depth_maps_written"] = depth_writer_.count();
  s["mean_map_points"] =
      confirmed_maps_ > 0 ? static_cast<double>(confirmed_points_) / confirmed_maps_ : 0.0;
  s["map_points_global"] = cloud_.size();
  const auto [rss_mb, peak_mb] = MemoryMb();
  s["peak_rss_mb"] = peak_mb;
  s["memory"] = {{"peak_rss_mb", peak_mb},
                 {"final_rss_mb", rss_mb},
                 {"over_time_columns", {"data_s", "rss_mb", "wall_s"}},
                 {"over_time", over_time_}};
  for (const auto& [stage, st] : timings_.Summary()) {
    s["stages"][stage] = {{"median_ms", st.median_ms},
                          {"p95_ms", st.p95_ms},
                          {"calls", st.calls},
                          {"median_items", st.median_items},
                          {"total_s", st.total_s}};
  }
  if (record.accuracy) s["accuracy"] = TrajectoryEvaluationJson(*record.accuracy);
  if (!record.accuracy_error.ok()) s["accuracy_error"] = record.accuracy_error.message();
  if (record.depth) s["depth"] = DepthJson(*record.depth);
  if (record.depth && record.sample_ceiling)
    s["depth"]["sample_ceiling"] = CoverageJson(*record.sample_ceiling);
  if (!failures.empty()) {
    s["incomplete_outputs"] = nlohmann::json::array();
    for (const Status& failure : failures)
      s["incomplete_outputs"].push_back(failure.message());
  }
  s.update(extra);
  keep(io::WriteTextFile((out / run_files::kSummary).string(), s.dump(2) + "\n"));
  if (!failures.empty()) return failures.front();
  return record;
}

}  // namespace aavio::recording
