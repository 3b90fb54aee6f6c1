// `aavio demo`: the whole tool in one command — simulate 6 s of the `rpg` preset (a hand-held
// DAVIS240C stereo pair with an IMU in a room), run the odometry on it, and print its accuracy
// against the simulator's ground truth and where the outputs are.
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "aavio/common/format.hpp"
#include "cli.hpp"
#include "option_checks.hpp"

namespace aavio::cli {
namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  std::string out_dir = "aavio_demo";
  std::string preset = "rpg";
  double duration_s = 6.0;  // 0: the preset's own length
  std::string sensor = "typical";
  std::uint64_t seed = 1;
  bool resimulate = false;
};

int RunDemo(const DemoOptions& options, Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path out(options.out_dir);
  // One sequence and run folder per sensor level, so that levels can be compared side by side.
  std::string suffix =
      options.sensor == "typical" ? "" : "_" + fs::path(options.sensor).stem().string();
  if (options.seed != 1) suffix += "_seed" + std::to_string(options.seed);
  const std::string sequence = (out / ("sequence" + suffix)).string();
  const std::string run = (out / ("run" + suffix)).string();
  if (options.resimulate || !fs::exists(fs::path(sequence) / "sequence.yaml")) {
    ctx.out << "1/2 simulating the '" << options.preset << "' preset with the " << options.sensor
            << " sensor into " << sequence << "\n";
    std::vector<std::string> args = {"aavio",   "simulate",   "--preset", options.preset,
                                     "--out",   sequence,     "--sensor", options.sensor,
                                     "--quiet", "--overwrite"};
    args.push_back("--seed");
    args.push_back(std::to_string(options.seed));
    if (options.duration_s > 0.0) {
      args.push_back("--duration");
      args.push_back(StrFormat("%g", options.duration_s));
    }
    const int code = RunCli(args, ctx.out, ctx.err);
    if (code != kExitOk) return code;
  } else {
    ctx.out << "1/2 reusing the simulated sequence in " << sequence << " (--resimulate to redo)\n";
  }
  ctx.out << "2/2 running the odometry: aavio run " << sequence << " --out " << run << "\n";
  // The demo's folders are its own: each demo replaces the previous one's run.
  const int code =
      RunCli({"aavio", "run", sequence, "--out", run, "--quiet", "--overwrite"}, ctx.out, ctx.err);
  if (code != kExitOk) return code;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ctx.out << StrFormat(
      "demo done in %.1f s. Look at %s/stamped_traj_estimate.txt (TUM), "
      "summary.json, map.ply and depth/; `aavio report --run %s` draws it; the ground truth is in "
      "%s/groundtruth.txt and %s/depth/.\n",
      wall, run.c_str(), run.c_str(), sequence.c_str(), sequence.c_str());
  return kExitOk;
}

}  // namespace

void RegisterDemo(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* sub =
      app.add_subcommand("demo", "Simulate a short sequence, run the odometry, print its accuracy");
  sub->add_option("--out", options->out_dir, "Output folder")->capture_default_str();
  sub->add_option("--preset", options->preset, "Simulation preset (mini, rpg, mvsec, dsec)")
      ->capture_default_str();
  sub->add_option("--duration", options->duration_s, "Seconds to simulate (0: the preset's length)")
      ->capture_default_str()
      ->check(NumberIn(0.0, 3600.0));
  sub->add_option("--sensor", options->sensor,
                  "Sensor model: ideal, typical or harsh, or a sensor YAML file")
      ->capture_default_str();
  sub->add_option("--seed", options->seed, "Seed of the scene, motion and sensor noise")
      ->capture_default_str()
      ->check(Seed());
  sub->add_flag("--resimulate", options->resimulate, "Simulate again even if the folder has data");
  sub->callback(
      [&ctx, options] { ctx.action = [&ctx, options] { return RunDemo(*options, ctx); }; });
}

}  // namespace aavio::cli
