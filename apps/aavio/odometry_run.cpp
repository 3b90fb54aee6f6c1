#include "odometry_run.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/prefetching_reader.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/mapping/global_cloud.hpp"
#include "aavio/mapping/rectified_stereo.hpp"
#include "aavio/pipeline/odometry.hpp"
#include "aavio/pipeline/stage_timings.hpp"
#include "config_resolution.hpp"
#include "mapping_counts.hpp"
#include "run_evaluation.hpp"

namespace aavio::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

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

const char* StatusName(tracking::TrackingStatus s) {
  switch (s) {
    case tracking::TrackingStatus::kOk: return "ok";
    case tracking::TrackingStatus::kLost: return "lost";
    case tracking::TrackingStatus::kNoMap: return "no_map";
  }
  return "?";
}

// Inverse depth as a colour (jet: red near, blue far, the paper's figures' convention) over the
// [rho_min, rho_max] range; BGR.
class InverseDepthColours {
 public:
  InverseDepthColours(double rho_min, double rho_max) : rho_min_(rho_min), rho_max_(rho_max) {
    cv::Mat level(1, 256, CV_8UC1);
    for (int i = 0; i < 256; ++i)
      level.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::applyColorMap(level, jet_, cv::COLORMAP_JET);
  }
  cv::Vec3b operator()(double rho) const {
    const double x = std::clamp((rho - rho_min_) / (rho_max_ - rho_min_), 0.0, 1.0);
    return jet_.at<cv::Vec3b>(0, static_cast<int>(std::lround(255.0 * x)));
  }

 private:
  double rho_min_, rho_max_;
  cv::Mat jet_;
};

// The local map's points, coloured by inverse depth, on black.
cv::Mat InverseDepthImage(const mapping::LocalMap& map, int width, int height,
                          const InverseDepthColours& colours) {
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(0, 0, 0));
  for (const mapping::DepthPoint& p : map.points) {
    const cv::Vec3b c = colours(p.rho);
    cv::circle(image, {static_cast<int>(std::lround(p.u)), static_cast<int>(std::lround(p.v))}, 1,
               cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
  }
  return image;
}

// The local map as disparity_INDEX.png (DSEC's ground-truth format: 16-bit, disparity × 256,
// 0 = none; 1/256 px steps, so 0.06 % of depth at 50 m on DSEC; a sparse map compresses to a few
// kB where float TIFF takes 1.2 MB) and as inverse_depth_INDEX.png (colour).
Status WriteDepthMaps(const fs::path& dir, const std::string& index, const mapping::LocalMap& map,
                      const mapping::RectifiedStereo& stereo, const InverseDepthColours& colours) {
  cv::Mat disparity(stereo.height, stereo.width, CV_16UC1, cv::Scalar(0));
  for (const mapping::DepthPoint& p : map.points) {
    const int u = static_cast<int>(std::lround(p.u)), v = static_cast<int>(std::lround(p.v));
    const double raw = std::round(256.0 * stereo.Disparity(p.rho));
    if (u >= 0 && v >= 0 && u < stereo.width && v < stereo.height && raw >= 1.0 && raw <= 65535.0)
      disparity.at<std::uint16_t>(v, u) = static_cast<std::uint16_t>(raw);
  }
  const std::string disparity_png = (dir / ("disparity_" + index + ".png")).string();
  const std::string colour_png = (dir / ("inverse_depth_" + index + ".png")).string();
  if (!cv::imwrite(disparity_png, disparity)) return IoError(disparity_png + ": cannot write");
  if (!cv::imwrite(colour_png, InverseDepthImage(map, stereo.width, stereo.height, colours)))
    return IoError(colour_png + ": cannot write");
  return Status::Ok();
}

Status WritePly(const std::string& path, const mapping::GlobalCloud& cloud,
                const InverseDepthColours& colours) {
  std::ofstream out(path, std::ios::binary);
  if (!out) return IoError(path + ": cannot write");
  out << "ply\nformat binary_little_endian 1.0\ncomment aavio global map (world frame, metres)\n"
      << "element vertex " << cloud.points().size()
      << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  for (std::size_t i = 0; i < cloud.points().size(); ++i) {
    const Eigen::Vector3f& p = cloud.points()[i];
    out.write(reinterpret_cast<const char*>(p.data()), 3 * sizeof(float));
    const cv::Vec3b c = colours(static_cast<double>(cloud.inv_depth()[i]));
    const char rgb[3] = {static_cast<char>(c[2]), static_cast<char>(c[1]), static_cast<char>(c[0])};
    out.write(rgb, 3);
  }
  return out ? Status::Ok() : IoError(path + ": write failed");
}

}  // namespace

Expected<OdometryRunResult> RunOdometry(const OdometryRunRequest& request, Context& ctx) {
  const auto wall_start = Clock::now();
  OpenedSequence& s = *request.sequence;
  const pipeline::OdometryConfig& config = *request.config;
  const geometry::StereoRig& rig = s.calibration.rig;
  std::error_code ec;
  fs::remove_all(fs::path(request.out_dir) / "depth", ec);  // no maps of an earlier run stay
  fs::create_directories(fs::path(request.out_dir) / "depth", ec);
  if (ec) return IoError(request.out_dir + ": cannot create the folder (" + ec.message() + ")");

  pipeline::Odometry odometry(rig, config, request.begin_ns);
  std::vector<geometry::StampedPose> trajectory;
  pipeline::StageTimings timings;
  std::map<std::string, int> status_counts, lost_reasons;
  int bootstraps = 0, reinitialisations = 0, cycles = 0, skipped_cycles = 0, mapping_cycles = 0;
  MappingCounts mapping_counts;
  std::ofstream csv(fs::path(request.out_dir) / "timings.csv");
  csv << "t_s,status,time_surface_ms,aa_ms,sampling_ms,tracking_ms,iterations,mapping_ms,"
         "map_points,lost_reason\n";
  // depth/: every `depth_every` mapping cycles (5 per second at the presets' 20 Hz) the local map
  // as disparity_INDEX.png (the layout of a sequence's ground-truth depth, so `aavio eval --run`
  // scores it) and as inverse_depth_INDEX.png (colour, the paper's figures).
  const int depth_every = std::max(1, static_cast<int>(std::lround(config.mapping.rate_hz / 5.0)));
  std::string depth_stamps = "# t[s] index\n";
  // map.ply: points up to the far end of the depth range (at most 50 m) on voxels of 0.5 % of it
  // (rpg 0.5–5 m: 2.5 cm; DSEC: 25 cm).
  const double cloud_depth_m = std::min(1.0 / config.mapping.inv_depth_min, 50.0);
  mapping::GlobalCloud cloud(0.005 * cloud_depth_m);
  const InverseDepthColours colours(config.mapping.inv_depth_min, config.mapping.inv_depth_max);
  nlohmann::json rss_over_time = nlohmann::json::array();
  Status write_status = Status::Ok();
  odometry.on_tick = [&](const pipeline::OdometryTick& t) {
    trajectory.push_back({t.t_ns, t.T_world_cam});
    status_counts[StatusName(t.status)]++;
    if (t.status == tracking::TrackingStatus::kLost)
      lost_reasons[tracking::LostReasonName(t.lost_reason)]++;
    timings.Add("time_surface", t.representation.time_surface_ms);
    timings.Add("ts_derived", t.representation.derived_ms);
    if (t.representation.edges) {  // mapping ticks only
      timings.Add("aa_map", t.representation.aa_ms);
      timings.Add("sampling", t.representation.sampling_ms);
    }
    if (t.status != tracking::TrackingStatus::kNoMap)
      timings.Add("tracking", t.tracking_ms, t.registration_iterations);
    if (t.mapping_wait_ms > 0.0) timings.Add("mapping_wait", t.mapping_wait_ms);
    bootstraps += t.bootstrap;
    skipped_cycles += t.mapping_skipped;
    reinitialisations += t.reinitialised;
    double mapping_ms = 0.0;
    mapping_cycles += t.mapped ? 1 : 0;
    if (t.mapped && !t.bootstrap) {
      const mapping::MappingCycleReport& r = t.mapping;
      mapping_counts.Add(r);
      timings.Add("matching", r.matching_ms, r.static_candidates + r.temporal_candidates);
      timings.Add("depth_refinement", r.refinement_ms, r.static_matches + r.temporal_matches);
      timings.Add("fusion", r.fusion_ms, r.map_points);
      timings.Add("mapping_total", r.total_ms, r.samples);
      mapping_ms = r.total_ms;
    }
    if (t.map && t.map->confirmed) {  // provisional maps are for tracking only
      cloud.Add(*t.map, cloud_depth_m);
      if (cycles % depth_every == 0 && write_status.ok()) {
        const std::string index = StrFormat("%06d", cycles / depth_every);
        write_status = WriteDepthMaps(fs::path(request.out_dir) / "depth", index, *t.map,
                                      mapping::RectifiedStereo::FromRig(rig), colours);
        depth_stamps += StrFormat("%.9f %s\n", NsToSeconds(t.map->t_ns), index.c_str());
      }
      ++cycles;
    }
    csv << StrFormat("%.6f,%s,%.4f,%.4f,%.4f,%.4f,%d,%.4f,%zu,%s\n", NsToSeconds(t.t_ns),
                     StatusName(t.status), t.representation.time_surface_ms,
                     t.representation.aa_ms, t.representation.sampling_ms, t.tracking_ms,
                     t.registration_iterations, mapping_ms, t.map ? t.map->points.size() : 0,
                     t.status == tracking::TrackingStatus::kLost
                         ? tracking::LostReasonName(t.lost_reason)
                         : "");
    if (odometry.ticks() % 100 == 0) {
      rss_over_time.push_back({NsToSeconds(t.t_ns - request.begin_ns), MemoryMb().first});
    }
  };

  std::int64_t events = 0;
  // Files are decoded on a thread of their own, up to 50 packets ahead.
  io::PrefetchingReader prefetching(s.reader.get(), 50);
  io::SensorPacket packet;
  bool interrupted = false;
  TimeNs last_t = request.begin_ns;
  while (true) {
    if (request.interrupted && request.interrupted->load()) {
      interrupted = true;
      break;
    }
    const auto read_start = Clock::now();
    Expected<bool> more = prefetching.Next(&packet);
    if (!more) return more.status();
    if (!*more || packet.t_begin_ns >= request.end_ns) break;
    const std::size_t packet_events = packet.left.size() + packet.right.size();
    events += static_cast<std::int64_t>(packet_events);
    timings.Add("event_reading",
                std::chrono::duration<double, std::milli>(Clock::now() - read_start).count(),
                static_cast<double>(packet_events));
    AAVIO_RETURN_IF_ERROR(odometry.Process(packet.left, packet.right, packet.imu,
                                           std::min(packet.t_end_ns, request.end_ns)));
    timings.Add("event_insertion", odometry.last_insertion_ms(),
                static_cast<double>(packet_events));
    AAVIO_RETURN_IF_ERROR(write_status);
    last_t = std::min(packet.t_end_ns, request.end_ns);
    if (request.progress && odometry.ticks() % 50 == 0) {
      const double done = NsToSeconds(last_t - request.begin_ns);
      const double wall = std::chrono::duration<double>(Clock::now() - wall_start).count();
      ctx.err << StrFormat("\rodometry %.1f / %.1f s of data, %.2fx real time, tracking ok %d, lost %d   ",
                           done, NsToSeconds(request.end_ns - request.begin_ns),
                           wall > 0 ? done / wall : 0.0, status_counts["ok"], status_counts["lost"])
              << std::flush;
    }
  }
  if (request.progress) ctx.err << "\r" << std::string(90, ' ') << "\r";
  csv.close();

  OdometryRunResult result;
  result.interrupted = interrupted;
  result.wall_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  result.data_s = NsToSeconds(last_t - request.begin_ns);
  result.poses = trajectory.size();
  const fs::path out(request.out_dir);
  AAVIO_RETURN_IF_ERROR(
      io::WriteTumTrajectory((out / "stamped_traj_estimate.txt").string(), trajectory));
  AAVIO_RETURN_IF_ERROR(io::WriteTextFile(
      (out / "config.yaml").string(),
      io::FormatConfigYaml(FlattenConfig(config), "aavio effective configuration (" +
                                                      VersionString() + ")\nfrom: " +
                                                      request.config_origin)));
  AAVIO_RETURN_IF_ERROR(WritePly((out / "map.ply").string(), cloud, colours));

  AAVIO_RETURN_IF_ERROR(
      io::WriteTextFile((out / "depth" / "timestamps.txt").string(), depth_stamps));

  // Accuracy against the sequence's ground truth, if it has one in TUM text (what `aavio eval
  // --run` computes, se3-aligned).
  const io::SequenceDescription& d = s.description;
  if (d.gt_trajectory && d.gt_trajectory->format == io::SourceFormat::kText && !trajectory.empty()) {
    Expected<RunGroundTruth> truth = LoadRunGroundTruth(d.origin);
    if (!truth) return truth.status();
    Expected<std::vector<geometry::StampedPose>> gt = io::ReadTumTrajectory(truth->trajectory_path);
    if (!gt) return gt.status();
    Expected<TrajectoryEvaluation> e = EvaluateTrajectories(trajectory, *gt, {});
    if (!e) return e.status().WithContext(truth->trajectory_path);
    result.accuracy = std::move(*e);
    if (!truth->depth_dir.empty() && cycles > 0) {
      Expected<eval::DepthErrorAccumulator> depth =
          EvaluateRunDepth((out / "depth").string(), *truth, *gt);
      if (depth) result.depth = depth->Summary();
    }
  }

  nlohmann::json summary;
  summary["mode"] = request.mode;
  summary["version"] = VersionString();
  summary["sequence"] = d.origin;
  summary["interrupted"] = interrupted;
  summary["data_duration_s"] = result.data_s;
  summary["wall_s"] = result.wall_s;
  summary["real_time_factor"] = result.wall_s > 0.0 ? result.data_s / result.wall_s : 0.0;
  summary["events"] = events;
  summary["poses"] = trajectory.size();
  summary["status"] = status_counts;
  summary["lost_reasons"] = lost_reasons;
  summary["bootstraps"] = bootstraps;
  summary["reinitialisations"] = reinitialisations;
  summary["real_time_mode"] = config.pipeline.real_time;
  summary["mapping_cycles"] = mapping_cycles;
  summary["mapping_cycles_skipped"] = skipped_cycles;
  summary["mapping_per_cycle"] = mapping_counts.PerCycleJson(mapping_cycles);
  summary["map_points_global"] = cloud.points().size();
  const auto [rss_mb, peak_mb] = MemoryMb();
  summary["peak_rss_mb"] = peak_mb;
  summary["memory"] = {{"peak_rss_mb", peak_mb}, {"final_rss_mb", rss_mb},
                       {"rss_mb_over_time", rss_over_time}};
  for (const auto& [stage, st] : timings.Summary()) {
    summary["stages"][stage] = {{"median_ms", st.median_ms},
                                {"p95_ms", st.p95_ms},
                                {"calls", st.calls},
                                {"median_items", st.median_items},
                                {"total_s", st.total_s}};
  }
  if (result.accuracy) summary["accuracy"] = TrajectoryEvaluationJson(*result.accuracy);
  if (result.depth) summary["depth"] = DepthJson(*result.depth);
  AAVIO_RETURN_IF_ERROR(io::WriteTextFile((out / "summary.json").string(), summary.dump(2) + "\n"));

  // The end-of-run summary.
  ctx.out << StrFormat("%s%.2f s of data (%lld events) in %.1f s: real-time factor %.2f\n",
                       interrupted ? "interrupted: " : "", result.data_s,
                       static_cast<long long>(events), result.wall_s,
                       result.wall_s > 0 ? result.data_s / result.wall_s : 0.0);
  ctx.out << StrFormat("poses %zu: tracking ok %d, lost %d, no map %d; %d bootstrap(s), %d re-initialisation(s)\n",
                       trajectory.size(), status_counts["ok"], status_counts["lost"],
                       status_counts["no_map"], bootstraps, reinitialisations);
  std::string stages = "median per stage [ms]:";
  for (const char* stage : {"time_surface", "ts_derived", "aa_map", "sampling", "tracking",
                            "matching", "depth_refinement", "fusion", "mapping_total"}) {
    const auto all = timings.Summary();
    if (auto it = all.find(stage); it != all.end())
      stages += StrFormat(" %s %.2f", stage, it->second.median_ms);
  }
  ctx.out << stages << "\n";
  if (result.accuracy) {
    const eval::TrajectoryError& e = result.accuracy->absolute;
    ctx.out << StrFormat(
        "accuracy vs ground truth (%zu poses, se3-aligned, path %.2f m): ATE RMSE %.4f m "
        "(%.2f %% of the path); RPE %.2f %%, %.3f deg/m; over %.1f s: %.4f m, %.3f deg\n",
        e.pairs, e.path_length_m, e.ate_rmse_m,
        e.path_length_m > 0 ? 100.0 * e.ate_rmse_m / e.path_length_m : 0.0,
        result.accuracy->relative.trans_pct_rmse, result.accuracy->relative.rot_deg_per_m_rmse,
        e.rpe_step_s, e.rpe_translation_rmse_m, e.rpe_rotation_rmse_deg);
  }
  if (result.depth) ctx.out << DepthTable(*result.depth);
  ctx.out << "wrote " << request.out_dir
          << "/{stamped_traj_estimate.txt,summary.json,timings.csv,config.yaml,map.ply,"
             "depth/}\n";
  return result;
}

}  // namespace aavio::cli
