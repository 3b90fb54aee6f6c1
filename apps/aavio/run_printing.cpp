// The lines `aavio run` ends with: what ran, how fast, how accurate, where the outputs are.
#include "run_printing.hpp"

#include <nlohmann/json.hpp>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/io/trajectory_writing.hpp"

namespace aavio::cli {
namespace {

void PrintOdometryRun(const recording::RunRecord& r, Context& ctx) {
  const nlohmann::json& s = r.summary;
  auto count = [&](const char* status) { return s["status"].value(status, 0); };
  ctx.out << StrFormat(
      "%s%.2f s of data (%lld events) in %.1f s: real-time factor %.2f, %.2f CPU-s per s of "
      "data\n",
      s["interrupted"].get<bool>() ? "interrupted: " : "", r.data_s, s["events"].get<long long>(),
      r.wall_s, s["real_time_factor"].get<double>(), s["cpu_s_per_data_s"].get<double>());
  const std::string imu = count("imu") > 0 ? StrFormat(", IMU alone %d", count("imu")) : "";
  ctx.out << StrFormat(
      "poses %zu: tracking ok %d, lost %d, no map %d%s; %d bootstrap(s), %d "
      "re-initialisation(s)\n",
      s["poses"].get<std::size_t>(), count("ok"), count("lost"), count("no_map"), imu.c_str(),
      s["bootstraps"].get<int>(), s["reinitialisations"].get<int>());
  if (s.contains("motion") && s["motion"].contains("poses_at")) {
    const nlohmann::json& p = s["motion"]["poses_at"];
    ctx.out << StrFormat("%s: %zu of the %zu stamps asked for",
                         p["file"].get<std::string>().c_str(), p["written"].get<std::size_t>(),
                         p["requested"].get<std::size_t>());
    if (p["missing"].get<std::size_t>() > 0) {
      ctx.out << StrFormat(
          "; %zu have no pose (%.3f-%.3f s: before or after the trajectory, or in a gap)",
          p["missing"].get<std::size_t>(), p["first_missing_s"].get<double>(),
          p["last_missing_s"].get<double>());
    }
    ctx.out << "\n";
  }
  for (const char* camera : {"left", "right"}) {
    if (s["event_gaps"][camera].empty()) continue;
    std::string line = StrFormat("no events from the %s camera:", camera);
    for (const nlohmann::json& gap : s["event_gaps"][camera])
      line += StrFormat(" %.2f-%.2f s", gap[0].get<double>(), gap[1].get<double>());
    ctx.out << line << "\n";
  }
  if (const auto dropped = s["dropped_events"].get<long long>(); dropped > 0) {
    ctx.out << StrFormat(
        "dropped %lld events: more than pipeline.max_buffered_events per camera waited for one "
        "tick (a burst)\n",
        dropped);
  }
  if (!s["event_gaps"]["skipped"].empty()) {
    std::string line =
        "no events from either camera (not ticked through; mapping restarted after):";
    for (const nlohmann::json& gap : s["event_gaps"]["skipped"])
      line += StrFormat(" %.2f-%.2f s", gap[0].get<double>(), gap[1].get<double>());
    ctx.out << line << "\n";
  }
  if (!s["imu_only"].empty()) {
    std::string line = "carried on the IMU alone (events missing or not registering):";
    for (const nlohmann::json& stretch : s["imu_only"])
      line += StrFormat(" %.2f-%.2f s", stretch[0].get<double>(), stretch[1].get<double>());
    ctx.out << line << "\n";
  }
  if (const int failed = s["bootstrap_failures"]["ticks"].get<int>(); failed > 0) {
    ctx.out << StrFormat(
        "bootstrap: %d tick(s) found too few points and tried again on the next "
        "(last: %s)\n",
        failed, s["bootstrap_failures"]["last_reason"].get<std::string>().c_str());
  }
  std::string stages = "median per stage [ms]:";
  for (const char* stage : {"time_surface", "ts_derived", "aa_map", "sampling", "tracking",
                            "matching", "depth_refinement", "fusion", "mapping_total"}) {
    if (s["stages"].contains(stage))
      stages += StrFormat(" %s %.2f", stage, s["stages"][stage]["median_ms"].get<double>());
  }
  ctx.out << stages << "\n";
  if (r.accuracy) {
    const eval::TrajectoryError& e = r.accuracy->absolute;
    ctx.out << StrFormat(
        "accuracy vs ground truth (%zu poses, se3-aligned, path %.2f m): ATE RMSE %.4f m "
        "(%.2f %% of the path); RPE %.2f %%, %.3f deg/m; over %.1f s: %.4f m, %.3f deg\n",
        e.pairs, e.path_length_m, e.ate_rmse_m,
        e.path_length_m > 0 ? 100.0 * e.ate_rmse_m / e.path_length_m : 0.0,
        r.accuracy->relative.trans_pct_rmse, r.accuracy->relative.rot_deg_per_m_rmse, e.rpe_step_s,
        e.rpe_translation_rmse_m, e.rpe_rotation_rmse_deg);
  }
}

}  // namespace

void PrintRun(const recording::RunRecord& record, const RunPrintout& run, Context& ctx) {
  const nlohmann::json& s = record.summary;
  if (run.mapping_only) {
    ctx.out << StrFormat(
        "%smapped %.2f s of data in %.1f s (real-time factor %.2f): %d cycles, %.0f map points "
        "per depth map\n",
        s["interrupted"].get<bool>() ? "interrupted: " : "", record.data_s, record.wall_s,
        s["real_time_factor"].get<double>(), s["mapping_cycles"].get<int>(),
        s["mean_map_points"].get<double>());
  } else {
    PrintOdometryRun(record, ctx);
  }
  if (run.tracking_error) {
    ctx.out << StrFormat(
        "tracked against ground-truth maps (imu.mode %s): RPE over 100 ms: rotation "
        "%.4f deg, translation %.4f m (RMSE)\n",
        run.imu_mode.c_str(), run.tracking_error->rotation_deg_rmse,
        run.tracking_error->translation_m_rmse);
  }
  if (record.depth) ctx.out << recording::DepthTable(*record.depth);
  if (record.calibration_error)
    ctx.out << recording::CalibrationDifferenceLine(
        *record.calibration_error, record.fb,
        "calibration against the true one (ground_truth.calibration)");
  if (record.sample_ceiling) ctx.out << recording::SampleCeilingLine(*record.sample_ceiling);
  std::string trajectories;
  if (s["poses"].get<std::size_t>() > 0) {
    trajectories = "stamped_traj_estimate.txt,stamped_velocity_estimate.txt,timings.csv,";
    if (s.contains("motion") && s["motion"].contains("poses_at"))
      trajectories += s["motion"]["poses_at"]["file"].get<std::string>() + ",";
    else if (run.format != io::TrajectoryFormat::kTum)
      trajectories += io::TrajectoryFileName(run.format) + ",";
  }
  const auto world = s.find("world");
  if (world != s.end() && world->contains("gravity_unavailable")) {
    ctx.err << "warning: --world gravity: the trajectory and map.ply stay in the first camera's "
               "frame: "
            << (*world)["gravity_unavailable"].get<std::string>() << "\n";
  } else if (world != s.end() && (*world)["frame"] == "gravity") {
    ctx.out << "world: z up along the measured gravity (summary.json world)\n";
  }
  ctx.out << "wrote " << run.out_dir << "/{" << trajectories << "summary.json,config.yaml,map.ply"
          << (s["depth_maps_written"].get<int>() > 0 ? ",depth/" : "") << "}\n";
}

}  // namespace aavio::cli
