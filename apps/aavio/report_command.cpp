// `aavio report --run DIR [--run DIR2 …]`: one html file (its figures embedded) about one or more
// runs — trajectories against ground truth, errors over time and distance, velocity, depth maps
// beside the ground truth, depth errors by true depth and edge kind, the IMU's estimates, timing
// against the real-time budget, and what differs between the runs' configurations. The numbers
// come from the same evaluation as `aavio eval --run` (report_data.cpp); the drawing is
// python3-matplotlib (Agg, headless) running the script embedded in this binary
// (report/plot_report.py), in a temporary folder removed afterwards.
#include <stdlib.h>  // mkdtemp

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/recording/run_recorder.hpp"
#include "cli.hpp"
#include "report/plot_report_script.hpp"
#include "report_data.hpp"

namespace aavio::cli {
namespace {

namespace fs = std::filesystem;

struct ReportOptions {
  std::vector<std::string> runs;
  std::vector<std::string> names;
  std::string out, calibration;
};

std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (const char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// A fresh folder for the plotting script's inputs and figures, removed when the report is done:
// the html file alone is the report.
class ScratchFolder {
 public:
  static Expected<ScratchFolder> Create() {
    std::string pattern = (fs::temp_directory_path() / "aavio_report_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr)
      return IoError(pattern + ": cannot create a temporary folder (is TMPDIR writable?)");
    return ScratchFolder(pattern);
  }
  ScratchFolder(ScratchFolder&& other) noexcept : path_(std::move(other.path_)) {
    other.path_.clear();
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ScratchFolder& operator=(ScratchFolder&&) = delete;
  ~ScratchFolder() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  explicit ScratchFolder(fs::path path) : path_(std::move(path)) {}
  fs::path path_;
};

// The interpreter: $AAVIO_PYTHON, else the first python3 that has matplotlib (the one on PATH may
// be a virtualenv's without it; Debian's is /usr/bin/python3).
Expected<std::string> FindPython() {
  std::vector<std::string> candidates = {"python3", "/usr/bin/python3"};
  if (const char* env = std::getenv("AAVIO_PYTHON")) candidates.insert(candidates.begin(), env);
  for (const std::string& candidate : candidates) {
    const std::string probe =
        ShellQuote(candidate) + " -c 'import matplotlib, numpy' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) return candidate;
  }
  return NotFound(
      "python3 with matplotlib and numpy is needed to draw the report: apt-get install "
      "python3-matplotlib (scripts/setup.sh installs it), or point AAVIO_PYTHON at an "
      "interpreter that has them");
}

Status Report(const ReportOptions& options, Context& ctx) {
  if (!options.names.empty() && options.names.size() != options.runs.size()) {
    return InvalidArgument(
        StrFormat("--name given %zu times for %zu --run folders; give one per run or none",
                  options.names.size(), options.runs.size()));
  }
  Expected<std::string> python = FindPython();
  if (!python) return python.status();
  // --out names the html file, or a folder to put report.html in.
  std::error_code ec;
  fs::path out_html =
      options.out.empty() ? fs::path(options.runs.front()) / "report.html" : fs::path(options.out);
  if (fs::is_directory(out_html, ec)) out_html /= "report.html";
  if (out_html.has_parent_path()) {
    fs::create_directories(out_html.parent_path(), ec);
    if (ec) {
      return IoError(out_html.parent_path().string() + ": cannot create the folder for --out (" +
                     ec.message() + ")");
    }
  }
  Expected<ScratchFolder> scratch = ScratchFolder::Create();
  if (!scratch) return scratch.status();
  const fs::path& data_dir = scratch->path();
  for (std::size_t i = 0; i < options.runs.size(); ++i) {
    ReportRun run{.dir = options.runs[i],
                  .name = options.names.empty() ? fs::path(options.runs[i]).filename().string()
                                                : options.names[i],
                  .calibration = options.calibration};
    if (run.name.empty()) run.name = fs::absolute(run.dir).parent_path().filename().string();
    Expected<nlohmann::json> data = GatherReportRun(run, data_dir, StrFormat("run_%zu", i), ctx);
    if (!data) return data.status().WithContext(run.dir);
    AAVIO_RETURN_IF_ERROR(
        io::WriteTextFile((data_dir / StrFormat("run_%zu.json", i)).string(), data->dump()));
    const fs::path timings = fs::path(run.dir) / recording::run_files::kTimings;
    if (fs::exists(timings))
      fs::copy_file(timings, data_dir / StrFormat("timings_%zu.csv", i),
                    fs::copy_options::overwrite_existing, ec);
  }
  for (const ReportScript& s : ReportScripts())
    AAVIO_RETURN_IF_ERROR(io::WriteTextFile((data_dir / s.file_name).string(), s.text));
  const fs::path script = data_dir / ReportScripts().front().file_name;
  const std::string command = "MPLBACKEND=Agg " + ShellQuote(*python) + " " +
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
      "report", "One html file (figures embedded) about one or more runs, compared on one page");
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
