// `aavio eval`: trajectory accuracy of an estimate against ground truth (`--est` + `--gt`), or of
// a run folder against the ground truth its sequence names (`--run`, with depth accuracy too);
// the definitions are those of rpg_trajectory_evaluation (docs/evaluation.md).
#include <CLI/CLI.hpp>
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
  std::string est, gt, run, sequence, calibration;
  std::string align = "se3";
  std::string format = "auto";  // of --est and --gt
  int align_frames = -1;
  double max_dt_s = 0.02;
  std::vector<double> lengths_m, fractions;
  bool json = false;
};

Status Evaluate(const EvalOptions& options, Context& ctx) {
  TrajectoryEvalOptions eval_options;
  Expected<eval::Alignment> alignment = eval::ParseAlignment(options.align);
  if (!alignment) return alignment.status().WithContext("--align");
  eval_options.alignment = *alignment;
  eval_options.align_frames = options.align_frames;
  eval_options.max_dt_s = options.max_dt_s;
  if (!options.fractions.empty()) eval_options.rpe.fractions = options.fractions;
  eval_options.rpe.lengths_m = options.lengths_m;

  Expected<io::TrajectoryFormat> format = io::TrajectoryFormatNamed(options.format);
  if (!format) return format.status().WithContext("--format");
  std::string est_path = options.est, gt_path = options.gt;
  std::optional<RunGroundTruth> truth;
  if (!options.run.empty()) {
    Expected<RunInputs> run = ReadRunInputs(options.run, options.sequence, options.calibration);
    if (!run) return run.status();
    Expected<RunGroundTruth> t = LoadRunGroundTruth(*run);
    if (!t) return t.status();
    truth = std::move(*t);
    est_path = (fs::path(options.run) / recording::run_files::kTrajectory).string();
    gt_path = truth->trajectory_name();
  }
  // A run on ground-truth poses (`aavio run --gt-poses`) has maps but no trajectory of its own.
  const bool has_estimate = options.run.empty() || fs::exists(est_path);
  // A run's ground truth is read as its sequence names it (text of any layout, or a bag topic).
  Expected<std::vector<geometry::StampedPose>> gt =
      truth ? truth->ReadPoses() : io::ReadTrajectory(gt_path, *format);
  if (!gt) return gt.status();
  std::optional<TrajectoryEvaluation> e;
  if (has_estimate) {
    Expected<std::vector<geometry::StampedPose>> est = io::ReadTrajectory(est_path, *format);
    if (!est) return est.status();
    Expected<TrajectoryEvaluation> evaluated = EvaluateTrajectories(*est, *gt, eval_options);
    if (!evaluated) return evaluated.status().WithContext(est_path + " vs " + gt_path);
    e = std::move(*evaluated);
  }

  std::optional<eval::DepthErrorSummary> depth;
  const fs::path run_depth = fs::path(options.run) / recording::run_files::kDepthDir;
  if (truth && !truth->depth_dir.empty() && fs::exists(run_depth / "timestamps.txt")) {
    Expected<eval::DepthErrorAccumulator> d = EvaluateRunDepth(run_depth.string(), *truth, *gt);
    if (!d) return d.status();
    depth = d->Summary();
  }
  if (!e && !depth) {
    return NotFound(options.run +
                    ": holds neither stamped_traj_estimate.txt nor depth maps with "
                    "ground truth to score them against");
  }
  if (options.json) {
    nlohmann::json j = e ? TrajectoryEvaluationJson(*e) : nlohmann::json::object();
    if (e) j["estimate"] = est_path;
    j["ground_truth"] = gt_path;
    if (depth) j["depth"] = DepthJson(*depth);
    ctx.out << j.dump(2) << "\n";
    return Status::Ok();
  }
  if (e) {
    ctx.out << "estimate     " << est_path << "\nground truth " << gt_path << "\n";
    ctx.out << TrajectoryEvaluationTable(*e);
  } else {
    ctx.out << "trajectory: none (a run on the ground-truth poses); depth maps of " << options.run
            << "/depth against " << truth->depth_dir << "\n";
  }
  if (depth)
    ctx.out << DepthTable(*depth);
  else if (truth && !truth->depth_dir.empty())
    ctx.out << "depth: the run has no depth/ maps (runs from before this version, or mapping "
               "never started)\n";
  return Status::Ok();
}

}  // namespace

void RegisterEval(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* sub = app.add_subcommand(
      "eval", "Trajectory accuracy (ATE, RPE) of an estimate, or of a run with its depth accuracy");
  sub->add_option("--est", options->est, "Estimated trajectory (TUM or EuRoC)");
  sub->add_option("--gt", options->gt, "Ground-truth trajectory (TUM or EuRoC), same clock");
  sub->add_option("--format", options->format,
                  "auto (told from each file), tum (stamps in s), tum_ns (in ns), euroc (CSV, "
                  "ns, w-first quaternion) or evslam (TUM + velocity)")
      ->capture_default_str();
  sub->add_option("--run", options->run,
                  "A run folder of `aavio run`: its trajectory and depth maps against the ground "
                  "truth its sequence names");
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
      if (pair == !options->run.empty() ||
          (pair && (options->est.empty() || options->gt.empty()))) {
        ctx.err << "aavio eval: give either --est TRAJ --gt TRAJ, or --run DIR\n";
        return static_cast<int>(kExitUsage);
      }
      const Status status = Evaluate(*options, ctx);
      if (status.ok()) return static_cast<int>(kExitOk);
      ctx.err << "aavio eval: error: " << status.message() << "\n";
      return static_cast<int>(kExitError);
    };
  });
}

}  // namespace aavio::cli
