#include "aavio/recording/run_recorder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/io/output_folder.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/recording/motion_outputs.hpp"
#include "aavio/recording/ply.hpp"

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

// CPU time of the whole process, every thread [s] (0 where the clock is missing).
double ProcessCpuSeconds() {
  timespec t{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) != 0) return 0.0;
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
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
                         const pipeline::OdometryConfig& config, MapOutputs maps,
                         io::DiskReserve reserve)
    : options_(std::move(options)),
      config_(config),
      stereo_(mapping::RectifiedStereo::FromRig(rig)),
      T_imu_cam_(rig.T_imu_rect_left()),
      wall_start_(Clock::now()),
      cpu_start_s_(ProcessCpuSeconds()),
      maps_(std::move(maps)),
      csv_((fs::path(options_.out_dir) / run_files::kTimings).string()),
      reserve_(std::move(reserve)),
      counts_(options_.begin_ns),
      event_gaps_(options_.begin_ns) {}

Expected<std::unique_ptr<RunRecorder>> RunRecorder::Open(RunRecorderOptions options,
                                                         const geometry::StereoRig& rig,
                                                         const pipeline::OdometryConfig& config) {
  const fs::path out(options.out_dir);
  AAVIO_RETURN_IF_ERROR(io::PrepareOutputFolder(
      options.out_dir, {.outputs = kRunOutputs, .overwrite = options.overwrite}));
  Expected<MapOutputs> maps =
      MapOutputs::Open((out / run_files::kDepthDir).string(), (out / run_files::kCloud).string(),
                       mapping::RectifiedStereo::FromRig(rig), config.mapping);
  if (!maps) return maps.status();
  Expected<io::DiskReserve> reserve =
      io::DiskReserve::Create((out / run_files::kReserve).string(), kReserveBytes);
  if (!reserve) return reserve.status();
  std::unique_ptr<RunRecorder> recorder(
      new RunRecorder(std::move(options), rig, config, std::move(*maps), std::move(*reserve)));
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
  csv_.AddEvents(static_cast<std::int64_t>(events));
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
  Expected<std::optional<cv::Mat>> written = maps_.Add(map, observation);
  if (!written) return written.status();
  if (!*written || !score_written || !scorer_) return Status::Ok();
  // Scored as `aavio eval --run` scores the file: the same disparities, turned into depth.
  const auto start = Clock::now();
  Expected<bool> scored = scorer_->AddDepthImage(
      map.t_ns, io::DepthFromDisparityImage(**written, truth_->fb, truth_->disparity_offset));
  evaluation_ms_ += MsSince(start);
  return scored.status();
}

Status RunRecorder::AddTick(const pipeline::OdometryTick& t) {
  AddRepresentation(t.t_ns, t.representation);
  trajectory_.push_back({t.t_ns, t.T_world_cam});
  trajectory_file_ << io::FormatTumPose(trajectory_.back());
  if (t.gap_before) event_gaps_.AddSkipped(t.gap_before->from_ns, t.gap_before->to_ns);
  event_gaps_.Add(t.t_ns, t.new_events_left, t.new_events_right);
  counts_.AddTick(t);
  if (t.status != tracking::TrackingStatus::kNoMap) {
    timings_.Add("tracking", t.tracking_ms, t.registration_iterations);
    timings_.Add("prediction", t.prediction_ms);
  }
  if (t.mapping_wait_ms > 0.0) timings_.Add("mapping_wait", t.mapping_wait_ms);
  double mapping_ms = 0.0;
  if (t.mapped && !t.bootstrap) {
    AddCycleReport(t.mapping);
    mapping_ms = t.mapping.total_ms;
  }
  if (t.map && t.map->confirmed)  // provisional maps are for tracking only
    AAVIO_RETURN_IF_ERROR(AddConfirmedMap(*t.map, t.map_observation.get(), /*score_written=*/true));
  AAVIO_RETURN_IF_ERROR(csv_.Add(t, mapping_ms));
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
  counts_.AddMappingCycle(cycle.bootstrap);
  ++mapping_cycles_on_ground_truth_;
  if (!cycle.bootstrap) AddCycleReport(cycle.report);
  const bool confirmed = cycle.map && cycle.map->confirmed;
  if (confirmed)
    AAVIO_RETURN_IF_ERROR(
        AddConfirmedMap(*cycle.map, cycle.observation.get(), /*score_written=*/false));
  // Only cycles whose samples went into the fusion count for the ceiling.
  const bool fused = cycle.bootstrap || cycle.report.fused_cycles > 0;
  if (!fused || !scorer_) return Status::Ok();
  const auto start = Clock::now();
  const Status scored = ScoreCycleOnGroundTruth(cycle, confirmed);
  evaluation_ms_ += MsSince(start);
  return scored;
}

Status RunRecorder::ScoreCycleOnGroundTruth(const pipeline::MappingCycle& cycle, bool confirmed) {
  Expected<std::optional<DepthScorer::Frame>> nearest = scorer_->Nearest(cycle.t_ns);
  if (!nearest) return nearest.status();
  if (!*nearest) return Status::Ok();
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

Expected<RunRecord> RunRecorder::Finish(bool interrupted, TimeNs end_ns,
                                        const nlohmann::json& extra) {
  RunRecord record;
  record.wall_s = std::chrono::duration<double>(Clock::now() - wall_start_).count();
  record.cpu_s = ProcessCpuSeconds() - cpu_start_s_;
  record.data_s = NsToSeconds(std::max(end_ns, options_.begin_ns) - options_.begin_ns);
  // Every file that can be written is, whatever failed before it (a full disk: the space held
  // back is given to these last files); the failures are listed in the summary.
  reserve_.reset();
  std::vector<Status> failures;
  std::optional<Eigen::Matrix3d> R_out_first;
  nlohmann::json motion = CloseFiles(&R_out_first, &failures);
  Score(&record);
  Summarize(interrupted, end_ns, std::move(motion), R_out_first, &record);
  nlohmann::json& s = record.summary;
  if (!failures.empty()) {
    s["incomplete_outputs"] = nlohmann::json::array();
    for (const Status& failure : failures)
      s["incomplete_outputs"].push_back(failure.message());
  }
  s.update(extra);
  const Status written = io::WriteTextFile(
      (fs::path(options_.out_dir) / run_files::kSummary).string(), s.dump(2) + "\n");
  if (!failures.empty()) return failures.front();
  if (!written.ok()) return written;
  return record;
}

nlohmann::json RunRecorder::CloseFiles(std::optional<Eigen::Matrix3d>* R_out_first,
                                       std::vector<Status>* failures) {
  auto keep = [failures](Status status) {
    if (!status.ok()) failures->push_back(std::move(status));
  };
  keep(csv_.Close());
  // Gravity, measured in the first camera's world; with World::kGravity the files are turned z-up.
  std::optional<imu::GravityDirection> gravity;
  if (T_imu_cam_) gravity = gravity_.Estimate(trajectory_, T_imu_cam_->R);
  if (options_.world == RunRecorderOptions::World::kGravity && gravity) {
    *R_out_first = gravity->R_up_world();
    for (geometry::StampedPose& p : trajectory_)
      p.T_world_body =
          geometry::RigidTransform(**R_out_first, Eigen::Vector3d::Zero()) * p.T_world_body;
  }
  keep(CloseTrajectory(/*rewrite=*/R_out_first->has_value()));
  nlohmann::json motion =
      WriteMotion({options_.out_dir, options_.format, options_.poses_at}, trajectory_, gravity,
                  R_out_first->value_or(Eigen::Matrix3d::Identity()), failures);
  keep(io::WriteTextFile((fs::path(options_.out_dir) / run_files::kConfig).string(),
                         options_.config_yaml));
  keep(maps_.CloseCloud(*R_out_first));
  keep(maps_.FinishDepth());
  return motion;
}

std::string RunRecorder::NeverMappedReason() const {
  if (!counts_.NeverMapped()) return "";
  const std::string& last = counts_.last_bootstrap_failure();
  return StrFormat(
      "no tick of the %zu had a map: the odometry never found a first one, so every "
      "pose is the start pose held, no estimate%s",
      trajectory_.size(), last.empty() ? "" : (" (the last attempt: " + last + ")").c_str());
}

void RunRecorder::Score(RunRecord* record) const {
  // Accuracy against the ground truth (what `aavio eval --run` computes, se3-aligned); why there
  // is none goes into the summary (accuracy_error), which is written all the same. Poses that
  // are all the start pose held are not scored.
  const std::string never_mapped = NeverMappedReason();
  if (truth_ && !trajectory_.empty() && !never_mapped.empty()) {
    record->accuracy_error = FailedPrecondition(never_mapped);
  } else if (truth_ && !trajectory_.empty()) {
    Expected<TrajectoryEvaluation> e = EvaluateTrajectories(trajectory_, gt_poses_, {});
    if (e) {
      record->accuracy = std::move(*e);
    } else {
      record->accuracy_error = e.status().WithContext(truth_->trajectory_name());
    }
  }
  if (truth_) {
    record->calibration_error = truth_->calibration_error;
    record->fb = truth_->fb;
  }
  if (scorer_) {
    eval::DepthErrorSummary depth = scorer_->accumulator().Summary();
    if (depth.frames > 0) record->depth = std::move(depth);
  }
  // The ceiling is scored on the cycles of a run on ground-truth poses only.
  if (ceiling_ && mapping_cycles_on_ground_truth_ > 0) record->sample_ceiling = ceiling_->Summary();
}

void RunRecorder::Summarize(bool interrupted, TimeNs end_ns, nlohmann::json motion,
                            const std::optional<Eigen::Matrix3d>& R_out_first, RunRecord* record) {
  const double evaluation_s = evaluation_ms_ / 1e3;
  const double processing_s = std::max(record->wall_s - evaluation_s, 0.0);
  nlohmann::json& s = record->summary;
  s["mode"] = options_.mode;
  s["world"] = WorldJson(options_.world, R_out_first);
  s["version"] = options_.version;
  s["sequence"] = options_.sequence;
  s["calibration"] = options_.calibration;
  s["motion"] = std::move(motion);
  s["interrupted"] = interrupted;
  s["data_duration_s"] = record->data_s;
  s["wall_s"] = record->wall_s;
  s["evaluation_s"] = evaluation_s;
  s["real_time_factor"] = processing_s > 0.0 ? record->data_s / processing_s : 0.0;
  // The scoring runs on the calling thread: its time is CPU time too, and left out the same way.
  const double cpu_s = std::max(record->cpu_s - evaluation_s, 0.0);
  s["cpu_s"] = cpu_s;
  s["cpu_s_per_data_s"] = record->data_s > 0.0 ? cpu_s / record->data_s : 0.0;
  s["events"] = events_;
  s["poses"] = trajectory_.size();
  counts_.AddTo(&s, trajectory_.empty() ? std::nullopt : std::optional(trajectory_.front().t_ns));
  event_gaps_.Finish(std::max(end_ns, options_.begin_ns));
  s["event_gaps"] = event_gaps_.Json();
  s["real_time_mode"] = config_.pipeline.real_time;
  s["mapping_per_cycle"] = mapping_counts_.PerCycleJson(counts_.mapping_cycles());
  maps_.AddTo(&s);
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
  if (record->accuracy) s["accuracy"] = TrajectoryEvaluationJson(*record->accuracy);
  if (!record->accuracy_error.ok()) s["accuracy_error"] = record->accuracy_error.message();
  if (record->depth) s["depth"] = DepthJson(*record->depth);
  if (record->calibration_error)
    s["calibration_error"] = CalibrationDifferenceJson(*record->calibration_error);
  if (record->depth && record->sample_ceiling)
    s["depth"]["sample_ceiling"] = CoverageJson(*record->sample_ceiling);
}

}  // namespace aavio::recording
