// `aavio report --run DIR [--run DIR2 …]`: plots of one or more runs — trajectories against ground
// truth (top and side), relative errors over distance, ATE along the path, depth-error histogram,
// per-stage timing — gathered in a self-contained report.html (images embedded). The numbers come
// from the same evaluation as `aavio eval --run`; the drawing is python3-matplotlib (Agg, headless)
// running the script embedded in this binary (report/plot_report.py).
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/recording/run_evaluation.hpp"
#include "aavio/recording/run_recorder.hpp"
#include "cli.hpp"
#include "report/plot_report_script.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {
namespace {

using recording::DepthJson;
using recording::EvaluateRunDepth;
using recording::EvaluateTrajectories;
using recording::RunGroundTruth;
using recording::TrajectoryEvaluation;
using recording::TrajectoryEvaluationJson;

namespace fs = std::filesystem;

struct ReportOptions {
  std::vector<std::string> runs;
  std::vector<std::string> names;
  std::string out, calibration;
};

// At most `n` evenly spaced elements (keeps plots and the html small on long runs).
template <typename T>
std::vector<T> Thin(const std::vector<T>& v, std::size_t n) {
  if (v.size() <= n) return v;
  std::vector<T> out;
  for (std::size_t i = 0; i < n; ++i)
    out.push_back(v[i * v.size() / n]);
  return out;
}

std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (const char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The trajectory against ground truth, thinned for the plots.
Expected<nlohmann::json> TrajectoryPlots(const std::string& estimate_path,
                                         const std::vector<geometry::StampedPose>& gt) {
  Expected<std::vector<geometry::StampedPose>> est = io::ReadTumTrajectory(estimate_path);
  if (!est) return est.status();
  Expected<TrajectoryEvaluation> e = EvaluateTrajectories(*est, gt, {});
  if (!e) return e.status().WithContext(estimate_path);
  nlohmann::json ev = TrajectoryEvaluationJson(*e);
  const std::vector<double> distance = eval::DistanceFromStart(e->pairs);
  std::vector<std::size_t> index(e->pairs.size());
  for (std::size_t i = 0; i < index.size(); ++i)
    index[i] = i;
  nlohmann::json positions_gt = nlohmann::json::array(), positions_est = nlohmann::json::array(),
                 ate = nlohmann::json::array(), dist = nlohmann::json::array();
  for (const std::size_t i : Thin(index, 5000)) {
    const eval::PosePair& p = e->pairs[i];
    const Eigen::Vector3d a = e->absolute.alignment.Apply(p.T_world_est.t);
    positions_gt.push_back({p.T_world_gt.t.x(), p.T_world_gt.t.y(), p.T_world_gt.t.z()});
    positions_est.push_back({a.x(), a.y(), a.z()});
    ate.push_back(e->absolute.ate_per_pair_m[i]);
    dist.push_back(distance[i]);
  }
  ev["positions_gt"] = positions_gt;
  ev["positions_est_aligned"] = positions_est;
  ev["ate_m"] = ate;
  ev["distance_m"] = dist;
  ev["relative"] = nlohmann::json::array();
  for (const eval::SubTrajectoryErrors& s : e->relative.per_length) {
    ev["relative"].push_back({{"length_m", s.length_m},
                              {"trans_pct", Thin(s.trans_pct, 2000)},
                              {"rot_deg_per_m", Thin(s.rot_deg_per_m, 2000)}});
  }
  return ev;
}

// Everything the plots of one run need, as JSON.
Expected<nlohmann::json> GatherRun(const std::string& dir, const std::string& name,
                                   const std::string& calibration, Context& ctx) {
  Expected<RunInputs> inputs = ReadRunInputs(dir, "", calibration);
  if (!inputs) return inputs.status();
  nlohmann::json run;
  run["summary"] = inputs->summary;
  run["name"] = name;
  run["dir"] = fs::absolute(dir).string();
  Expected<RunGroundTruth> truth = LoadRunGroundTruth(*inputs);
  const fs::path estimate_path = fs::path(dir) / recording::run_files::kTrajectory;
  if (!truth) {
    ctx.err << "aavio report: " << dir << ": no ground truth to evaluate against ("
            << truth.status().message() << "); plotting timings only\n";
    return run;
  }
  Expected<std::vector<geometry::StampedPose>> gt = truth->ReadPoses();
  if (!gt) return gt.status();
  // A run on ground-truth poses has depth maps but no trajectory of its own.
  if (fs::exists(estimate_path)) {
    Expected<nlohmann::json> ev = TrajectoryPlots(estimate_path.string(), *gt);
    if (!ev) return ev.status();
    run["evaluation"] = *ev;
  }
  const fs::path depth_dir = fs::path(dir) / recording::run_files::kDepthDir;
  if (!truth->depth_dir.empty() && fs::exists(depth_dir / "timestamps.txt")) {
    Expected<eval::DepthErrorAccumulator> depth = EvaluateRunDepth(depth_dir.string(), *truth, *gt);
    if (!depth) return depth.status();
    run["depth"] = DepthJson(depth->Summary());
    run["depth_relative_errors"] = Thin(depth->relative_errors(), 50000);
  }
  return run;
}

Status Report(const ReportOptions& options, Context& ctx) {
  if (!options.names.empty() && options.names.size() != options.runs.size()) {
    return InvalidArgument(
        StrFormat("--name given %zu times for %zu --run folders; give one per run or none",
                  options.names.size(), options.runs.size()));
  }
  // --out names the html file, or a folder to put report.html in.
  std::error_code ec;
  fs::path out_html =
      options.out.empty() ? fs::path(options.runs.front()) / "report.html" : fs::path(options.out);
  if (fs::is_directory(out_html, ec)) out_html /= "report.html";
  const fs::path data_dir = out_html.parent_path() / (out_html.stem().string() + "_files");
  fs::create_directories(data_dir, ec);
  if (ec) return IoError(data_dir.string() + ": cannot create the folder (" + ec.message() + ")");
  for (const auto& entry : fs::directory_iterator(data_dir, ec))
    if (entry.path().extension() == ".json" || entry.path().extension() == ".csv")
      fs::remove(entry.path(), ec);
  for (std::size_t i = 0; i < options.runs.size(); ++i) {
    const std::string& dir = options.runs[i];
    std::string name = options.names.empty() ? fs::path(dir).filename().string() : options.names[i];
    if (name.empty()) name = fs::absolute(dir).parent_path().filename().string();
    Expected<nlohmann::json> run = GatherRun(dir, name, options.calibration, ctx);
    if (!run) return run.status();
    AAVIO_RETURN_IF_ERROR(
        io::WriteTextFile((data_dir / StrFormat("run_%zu.json", i)).string(), run->dump()));
    const fs::path timings = fs::path(dir) / "timings.csv";
    if (fs::exists(timings))
      fs::copy_file(timings, data_dir / StrFormat("timings_%zu.csv", i),
                    fs::copy_options::overwrite_existing, ec);
  }
  const fs::path script = data_dir / "plot_report.py";
  AAVIO_RETURN_IF_ERROR(io::WriteTextFile(script.string(), PlotReportScript()));
  // The interpreter: $AAVIO_PYTHON, else the first python3 that has matplotlib (the one on PATH may
  // be a virtualenv's without it; Debian's is /usr/bin/python3).
  std::string python;
  std::vector<std::string> candidates = {"python3", "/usr/bin/python3"};
  if (const char* env = std::getenv("AAVIO_PYTHON")) candidates.insert(candidates.begin(), env);
  for (const std::string& candidate : candidates) {
    const std::string probe = ShellQuote(candidate) + " -c 'import matplotlib' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) {
      python = candidate;
      break;
    }
  }
  if (python.empty()) {
    return NotFound(
        "python3 with matplotlib is needed to draw the report: apt-get install "
        "python3-matplotlib (scripts/setup.sh installs it), or point AAVIO_PYTHON at "
        "an interpreter that has it");
  }
  const std::string command = "MPLBACKEND=Agg " + ShellQuote(python) + " " +
                              ShellQuote(script.string()) + " " + ShellQuote(data_dir.string()) +
                              " " + ShellQuote(out_html.string());
  if (std::system(command.c_str()) != 0)
    return FailedPrecondition("the plotting script failed (its message is above): " + command);
  return Status::Ok();
}

}  // namespace

void RegisterReport(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "Plots and a self-contained report.html of one or more runs (compared on one page)");
  sub->add_option("--run", options->runs, "A run folder of `aavio run` (repeat to compare runs)")
      ->required();
  sub->add_option("--name", options->names, "A label per run (default: the folder name)");
  sub->add_option("--calib", options->calibration,
                  "The calibration, for runs that do not record one that still exists");
  sub->add_option("--out", options->out,
                  "The html file, or a folder for report.html (default: FIRST_RUN/report.html)");
  sub->callback([&ctx, options] {
    ctx.action = [&ctx, options] {
      const Status status = Report(*options, ctx);
      if (status.ok()) return static_cast<int>(kExitOk);
      ctx.err << "aavio report: error: " << status.message() << "\n";
      return static_cast<int>(kExitError);
    };
  });
}

}  // namespace aavio::cli
