// `aavio eval`: trajectory accuracy of an estimate against ground truth (`--est` + `--gt`), or of
// a run folder against the ground truth its sequence names (`--run`, with depth accuracy too);
// the definitions are those of rpg_trajectory_evaluation (docs/evaluation.md).
#include <CLI/CLI.hpp>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/mapping/rectified_stereo.hpp"
#include "aavio/recording/run_evaluation.hpp"
#include "aavio/recording/run_recorder.hpp"
#include "cli.hpp"
#include "option_checks.hpp"
#include "results_table.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {
namespace {

using recording::DepthJson;
using recording::DepthTable;
using recording::EvaluateRunDepth;
using recording::EvaluateTrajectories;
using recording::RunGroundTruth;
using recording::TrajectoryEvalOptions;
using recording::TrajectoryEvaluation;
using recording::TrajectoryEvaluationJson;
using recording::TrajectoryEvaluationTable;

namespace fs = std::filesystem;

struct EvalOptions {
  std::string est, gt, sequence, calibration, times;
  std::vector<std::string> runs, names;
  std::string align = "se3";
  std::string format = "auto";  // of --est and --gt
  std::string table = "md";     // several runs
  int align_frames = -1;
  double max_dt_s = 0.02;
  std::vector<double> lengths_m, fractions;
  bool json = false;
};

// One estimate scored: a trajectory pair, or a run folder (`run_dir` not empty).
struct Scored {
  std::string est_path, gt_path;
  std::string note;  // how the estimate was turned, or why posyaw may mislead
  std::optional<RunGroundTruth> truth;
  std::optional<TrajectoryEvaluation> trajectory;
  std::optional<eval::DepthErrorSummary> depth;
  nlohmann::json summary;  // the run's summary.json
};

Expected<TrajectoryEvalOptions> TrajectoryOptions(const EvalOptions& options) {
  TrajectoryEvalOptions eval_options;
  Expected<eval::Alignment> alignment = eval::ParseAlignment(options.align);
  if (!alignment) return alignment.status().WithContext("--align");
  eval_options.alignment = *alignment;
  eval_options.align_frames = options.align_frames;
  eval_options.max_dt_s = options.max_dt_s;
  if (!options.fractions.empty()) eval_options.rpe.fractions = options.fractions;
  eval_options.rpe.lengths_m = options.lengths_m;
  return eval_options;
}

// posyaw rotates about z only, so both worlds must have z up: a run's world is its first camera's,
// turned here by the gravity direction the run measured (summary.json motion.gravity).
std::string TurnZUp(const nlohmann::json& summary, std::vector<geometry::StampedPose>* poses) {
  // A summary is the user's file: every entry is checked before it is read.
  std::array<double, 4> q{};
  double magnitude = 0.0;
  bool found = false;
  const auto motion = summary.find("motion");
  if (motion != summary.end() && motion->is_object()) {
    const auto g = motion->find("gravity");
    if (g != motion->end() && g->is_object()) {
      const auto qs = g->find("q_up_world_xyzw");
      const auto m = g->find("magnitude_m_s2");
      found =
          qs != g->end() && qs->is_array() && qs->size() == 4 && m != g->end() && m->is_number();
      for (std::size_t k = 0; found && k < 4; ++k) {
        found = (*qs)[k].is_number();
        if (found) q[k] = (*qs)[k].get<double>();
      }
      if (found) magnitude = m->get<double>();
    }
  }
  const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  if (!found || !(rotation.norm() > 0.5)) {
    return "note: posyaw rotates about z alone and so assumes both worlds have z up; the estimate "
           "has no measured gravity to turn it by (a run with an IMU and its extrinsic, 2 s or "
           "more, has one)";
  }
  const auto world = summary.find("world");
  if (world != summary.end() && world->is_object() && world->contains("frame") &&
      (*world)["frame"] == "gravity")
    return "the run's world is z-up along its measured gravity already (aavio run --world gravity)";
  const Eigen::Matrix3d R_up = rotation.normalized().toRotationMatrix();
  for (geometry::StampedPose& p : *poses) {
    p.T_world_body.R = R_up * p.T_world_body.R;
    p.T_world_body.t = R_up * p.T_world_body.t;
  }
  return StrFormat("the estimate turned z-up by the gravity the run measured (%.2f m/s^2)",
                   magnitude);
}

// The velocities a file gives (EvSLAM's linear velocity; the angular one derived from its poses),
// or none.
std::vector<geometry::StampedVelocity> GivenVelocities(const io::TrajectoryFile& file,
                                                       TimeNs half_window_ns) {
  if (file.v_body_mps.size() != file.poses.size() || file.poses.empty()) return {};
  std::vector<geometry::StampedVelocity> v =
      geometry::EstimateVelocities(file.poses, half_window_ns);
  for (std::size_t i = 0; i < v.size(); ++i) {
    v[i].v_body_mps = file.v_body_mps[i];
    v[i].valid = true;
  }
  return v;
}

Expected<Scored> Score(const EvalOptions& options, const std::string& run_dir) {
  Expected<TrajectoryEvalOptions> eval_options = TrajectoryOptions(options);
  if (!eval_options) return eval_options.status();
  Expected<io::TrajectoryFormat> format = io::TrajectoryFormatNamed(options.format);
  if (!format) return format.status().WithContext("--format");
  Scored r;
  r.est_path = options.est;
  r.gt_path = options.gt;
  if (!run_dir.empty()) {
    Expected<RunInputs> run = ReadRunInputs(run_dir, options.sequence, options.calibration);
    if (!run) return run.status();
    r.summary = run->summary;
    Expected<RunGroundTruth> t = LoadRunGroundTruth(*run);
    if (!t) return t.status().WithContext(run_dir);
    r.truth = std::move(*t);
    r.est_path = (fs::path(run_dir) / recording::run_files::kTrajectory).string();
    r.gt_path = r.truth->trajectory_name();
  }
  // A run on ground-truth poses (`aavio run --gt-poses`) has maps but no trajectory of its own.
  const bool has_estimate = run_dir.empty() || fs::exists(r.est_path);
  // KITTI files take their stamps from --times; two KITTI files without it pair line by line.
  std::optional<std::vector<TimeNs>> kitti_stamps;
  if (!options.times.empty()) {
    Expected<std::vector<TimeNs>> times = io::ReadStamps(options.times);
    if (!times) return times.status().WithContext("--times");
    kitti_stamps = std::move(*times);
  } else if (run_dir.empty()) {
    auto is_kitti = [&](const std::string& path) {
      if (*format != io::TrajectoryFormat::kAuto) return *format == io::TrajectoryFormat::kKitti;
      Expected<io::TrajectoryFormat> f = io::DetectTrajectoryFormat(path);
      return f.ok() && *f == io::TrajectoryFormat::kKitti;
    };
    if (is_kitti(r.est_path) && is_kitti(r.gt_path)) kitti_stamps.emplace();
  }
  const std::vector<TimeNs>* stamps = kitti_stamps ? &*kitti_stamps : nullptr;
  // A run's ground truth is read as its sequence names it (text of any layout, or a bag topic).
  io::TrajectoryFile gt;
  if (r.truth) {
    Expected<std::vector<geometry::StampedPose>> poses = r.truth->ReadPoses();
    if (!poses) return poses.status();
    gt.poses = std::move(*poses);
  } else {
    Expected<io::TrajectoryFile> read = io::ReadTrajectoryFile(r.gt_path, *format, stamps);
    if (!read) return read.status();
    gt = std::move(*read);
  }
  if (has_estimate) {
    Expected<io::TrajectoryFile> est = io::ReadTrajectoryFile(r.est_path, *format, stamps);
    if (!est) return est.status();
    if (eval_options->alignment == eval::Alignment::kPosYaw)
      r.note = TurnZUp(r.summary, &est->poses);
    if (est->format == io::TrajectoryFormat::kKitti && gt.format == io::TrajectoryFormat::kKitti &&
        stamps && stamps->empty() && est->poses.size() != gt.poses.size()) {
      return InvalidArgument(StrFormat(
          "%s has %zu poses and %s %zu: KITTI files without --times pair line by line, so they "
          "must be the same length (give the sequence's times.txt with --times)",
          r.est_path.c_str(), est->poses.size(), r.gt_path.c_str(), gt.poses.size()));
    }
    const std::vector<geometry::StampedVelocity> est_v =
        GivenVelocities(*est, eval_options->velocity_half_window_ns);
    const std::vector<geometry::StampedVelocity> gt_v =
        GivenVelocities(gt, eval_options->velocity_half_window_ns);
    Expected<TrajectoryEvaluation> evaluated =
        EvaluateTrajectories(est->poses, gt.poses, *eval_options, est_v.empty() ? nullptr : &est_v,
                             gt_v.empty() ? nullptr : &gt_v);
    if (!evaluated) return evaluated.status().WithContext(r.est_path + " vs " + r.gt_path);
    r.trajectory = std::move(*evaluated);
  }
  const fs::path run_depth = fs::path(run_dir) / recording::run_files::kDepthDir;
  if (r.truth && !r.truth->depth_dir.empty() && fs::exists(run_depth / "timestamps.txt")) {
    Expected<eval::DepthErrorAccumulator> d =
        EvaluateRunDepth(run_depth.string(), *r.truth, gt.poses);
    if (!d) return d.status();
    r.depth = d->Summary();
  }
  if (!r.trajectory && !r.depth) {
    return NotFound(run_dir +
                    ": holds neither stamped_traj_estimate.txt nor depth maps with "
                    "ground truth to score them against");
  }
  return r;
}

nlohmann::json ScoredJson(const Scored& r) {
  nlohmann::json j =
      r.trajectory ? TrajectoryEvaluationJson(*r.trajectory) : nlohmann::json::object();
  if (r.trajectory) j["estimate"] = r.est_path;
  if (!r.note.empty()) j["note"] = r.note;
  j["ground_truth"] = r.gt_path;
  if (r.depth) j["depth"] = DepthJson(*r.depth);
  return j;
}

Status Evaluate(const EvalOptions& options, Context& ctx) {
  const std::string run_dir = options.runs.empty() ? "" : options.runs.front();
  Expected<Scored> r = Score(options, run_dir);
  if (!r) return r.status();
  if (options.json) {
    ctx.out << ScoredJson(*r).dump(2) << "\n";
    return Status::Ok();
  }
  if (r->trajectory) {
    ctx.out << "estimate     " << r->est_path << "\nground truth " << r->gt_path << "\n";
    if (!r->note.empty()) ctx.out << r->note << "\n";
    ctx.out << TrajectoryEvaluationTable(*r->trajectory);
  } else {
    ctx.out << "trajectory: none (a run on the ground-truth poses); depth maps of " << run_dir
            << "/depth against " << r->truth->depth_dir << "\n";
  }
  if (r->depth)
    ctx.out << DepthTable(*r->depth);
  else if (r->truth && !r->truth->depth_dir.empty())
    ctx.out << "depth: the run has no depth/ maps (runs from before this version, or mapping "
               "never started)\n";
  return Status::Ok();
}

// Several runs: one row each (evo_res's table), in --table's form; --json: one object per run.
Status EvaluateMany(const EvalOptions& options, Context& ctx) {
  Expected<TableFormat> table = TableFormatNamed(options.table);
  if (!table) return table.status().WithContext("--table");
  const std::vector<std::string> header = {
      "run",        "ATE [m]",       "ATE [%]",  "rot. [deg] (orient.-aligned)",
      "RPE t [%]",  "RPE R [deg/m]", "vel. AUC", "depth [%]",
      "lost ticks", "real time [x]"};
  std::vector<std::vector<std::string>> rows;
  nlohmann::json all = nlohmann::json::array();
  for (std::size_t i = 0; i < options.runs.size(); ++i) {
    const std::string& dir = options.runs[i];
    Expected<Scored> r = Score(options, dir);
    if (!r) return r.status();
    std::string name = options.names.empty() ? fs::path(dir).filename().string() : options.names[i];
    if (name.empty()) name = fs::path(dir).parent_path().filename().string();
    nlohmann::json j = ScoredJson(*r);
    j["run"] = name;
    all.push_back(j);
    std::vector<std::string> row = {name};
    if (r->trajectory) {
      const eval::TrajectoryError& a = r->trajectory->absolute;
      // Orientation-aligned: free of how well each path fixes the alignment's rotation, so
      // comparable between runs of different paths (docs/evaluation.md §4).
      const double rotation = a.ate_rotation_rmse_orientation_aligned_deg;
      row.push_back(StrFormat("%.4f", a.ate_rmse_m));
      row.push_back(a.path_length_m > 0 ? StrFormat("%.2f", 100.0 * a.ate_rmse_m / a.path_length_m)
                                        : "");
      row.push_back(StrFormat("%.3f", rotation));
      row.push_back(StrFormat("%.2f", r->trajectory->relative.trans_pct_rmse));
      row.push_back(StrFormat("%.3f", r->trajectory->relative.rot_deg_per_m_rmse));
      row.push_back(
          r->trajectory->velocity.pairs > 0 ? StrFormat("%.3f", r->trajectory->velocity.auc) : "");
    } else {
      row.insert(row.end(), 6, "");
    }
    row.push_back(r->depth ? StrFormat("%.2f", 100.0 * r->depth->relative) : "");
    // From the run's summary.json, where it holds them as numbers.
    const nlohmann::json& s = r->summary;
    const auto status = s.find("status");
    std::string lost;
    if (status != s.end() && status->is_object()) {
      const auto n = status->find("lost");
      lost = n != status->end() && n->is_number_integer() ? std::to_string(n->get<long long>())
                                                          : "0";  // only counts that occurred
    }
    row.push_back(lost);
    const auto factor = s.find("real_time_factor");
    row.push_back(
        factor != s.end() && factor->is_number() ? StrFormat("%.2f", factor->get<double>()) : "");
    rows.push_back(std::move(row));
  }
  if (options.json) {
    ctx.out << all.dump(2) << "\n";
    return Status::Ok();
  }
  ctx.out << FormatTable(header, rows, *table);
  return Status::Ok();
}

}  // namespace

void RegisterEval(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand(
      "eval", "Trajectory accuracy (ATE, RPE) of an estimate, or of a run with its depth accuracy");
  sub->add_option("--est", options->est, "Estimated trajectory (TUM, EuRoC, EvSLAM or KITTI)");
  sub->add_option("--gt", options->gt, "Ground-truth trajectory (same layouts), same clock");
  sub->add_option("--format", options->format,
                  "auto (told from each file), tum (stamps in s), tum_ns (in ns), euroc (CSV, "
                  "ns, w-first quaternion), evslam (TUM + velocity) or kitti (3x4 rows, --times)")
      ->capture_default_str();
  sub->add_option("--times", options->times,
                  "KITTI files' stamps (their times.txt, s); without it two KITTI files pair line "
                  "by line");
  sub->add_option("--run", options->runs,
                  "A run folder of `aavio run`: its trajectory and depth maps against the ground "
                  "truth its sequence names (repeat: one table of all, see --table)");
  sub->add_option("--name", options->names, "With several --run: a label per run");
  sub->add_option("--table", options->table, "With several --run: md, csv or latex")
      ->capture_default_str();
  sub->add_option("--sequence", options->sequence,
                  "With --run: the sequence, if it moved since the run");
  sub->add_option("--calib", options->calibration,
                  "With --run: the calibration, if the run does not record one that still exists");
  sub->add_option("--align", options->align, "se3 | sim3 | posyaw | none")->capture_default_str();
  sub->add_option("--align-frames", options->align_frames,
                  "Align on the first N pose pairs only (-1: all)")
      ->capture_default_str()
      ->check(NumberIn(-1, 1 << 30));
  sub->add_option("--max-dt", options->max_dt_s, "Association window [s]")
      ->capture_default_str()
      ->check(NumberIn(1e-6, 10.0));
  sub->add_option("--lengths", options->lengths_m,
                  "RPE sub-trajectory lengths [m] (default: 10,20,30,40,50 % of the path)")
      ->delimiter(',')
      ->check(NumberIn(1e-6, 1e7));
  sub->add_option("--fractions", options->fractions,
                  "RPE sub-trajectory lengths as fractions of the path")
      ->delimiter(',')
      ->check(NumberIn(1e-6, 1.0));
  sub->add_flag("--json", options->json, "Print JSON (keys: docs/evaluation.md)");
  sub->callback([&ctx, options] {
    ctx.action = [&ctx, options] {
      const bool pair = !options->est.empty() || !options->gt.empty();
      if (pair == !options->runs.empty() ||
          (pair && (options->est.empty() || options->gt.empty()))) {
        ctx.err << "aavio eval: give either --est TRAJ --gt TRAJ, or --run DIR (repeatable)\n";
        return static_cast<int>(kExitUsage);
      }
      if (!options->names.empty() && options->names.size() != options->runs.size()) {
        ctx.err << "aavio eval: --name given " << options->names.size() << " times for "
                << options->runs.size() << " --run folders; give one per run or none\n";
        return static_cast<int>(kExitUsage);
      }
      if (options->runs.size() > 1 && !options->sequence.empty()) {
        ctx.err << "aavio eval: --sequence names one run's sequence; with several --run, "
                   "evaluate the moved one on its own\n";
        return static_cast<int>(kExitUsage);
      }
      const Status status =
          options->runs.size() > 1 ? EvaluateMany(*options, ctx) : Evaluate(*options, ctx);
      if (status.ok()) return static_cast<int>(kExitOk);
      ctx.err << "aavio eval: error: " << status.message() << "\n";
      return static_cast<int>(kExitError);
    };
  });
}

}  // namespace aavio::cli
