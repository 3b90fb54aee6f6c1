// `aavio run`: mapping with ground-truth poses, tracking on ground-truth maps, the bootstrap
// and the full odometry's outputs and determinism.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "aavio/common/format.hpp"
#include "aavio/common/time.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/recording/ply.hpp"
#include "cli.hpp"
#include "cli_test_util.hpp"
#include "tests/event_fixtures.hpp"
#include "tests/fixtures/calibrations.hpp"
#include "tests/test_utils.hpp"

namespace aavio::cli {
namespace {

using testing_cli::Result;
using testing_cli::RunAavio;

TEST(Cli, RunMapsWithGroundTruthPosesAndScoresDepth) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string(), out = (dir / "run").string();
  // The ideal sensor: the sample ceiling bounds the map only when the calibration is the truth
  // (with the typical sensor, the map is made with the erroneous calibration it is handed).
  Result r = RunAavio({"simulate", "--preset", "mini", "--duration", "1.5", "--out", seq,
                       "--sensor", "ideal", "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  r = RunAavio({"run", seq, "--gt-poses", "--out", out, "--preset", "indoor", "--quiet", "--set",
                "mapping.bootstrap.min_points=100"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("depth ("), std::string::npos) << r.out;
  std::ifstream in(std::filesystem::path(out) / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_GT(j["mapping_cycles"].get<int>(), 10);  // 1.5 s at the preset's 10 Hz
  EXPECT_GT(j["depth"]["points"].get<int>(), 1000);
  EXPECT_LT(j["depth"]["relative_median"].get<double>(), 0.1);  // a real map, not noise
  // The samples at their true depth cover at least what the map does, and not everything.
  const nlohmann::json& ceiling = j["depth"]["sample_ceiling"];
  for (const char* key : {"completeness", "completeness_near_horizontal", "block_coverage"}) {
    EXPECT_GE(ceiling[key].get<double>(), j["depth"][key].get<double>()) << key;
    EXPECT_LT(ceiling[key].get<double>(), 1.0) << key;
  }
  EXPECT_NE(r.out.find("edge samples at their true depth would cover"), std::string::npos);
  for (const char* stage : {"time_surface", "aa_map", "sampling", "matching", "depth_refinement",
                            "fusion", "mapping_total"}) {
    EXPECT_TRUE(j["stages"].contains(stage)) << stage;
  }
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "config.yaml"));
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "map.ply"));
  // `aavio eval --run` scores the maps the run wrote to depth/ (it has no trajectory of its own).
  r = RunAavio({"eval", "--run", out, "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json e = nlohmann::json::parse(r.out);
  EXPECT_FALSE(e.contains("ate_rmse_m"));
  EXPECT_GT(e["depth"]["frames"].get<int>(), 0);
  EXPECT_EQ(e["depth"]["frames"].get<int>(), j["depth_maps_written"].get<int>());
  EXPECT_LT(e["depth"]["relative_median"].get<double>(), 0.1);
  // Without --preset, mapping alone takes the sensor's settings and the preset the rig suggests,
  // as the odometry does.
  const std::string auto_out = (dir / "run_auto").string();
  r = RunAavio(
      {"run", seq, "--gt-poses", "--out", auto_out, "--set", "mapping.bootstrap.min_points=100"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.err.find("no --preset given; using 'indoor' (baseline 0.15 m"), std::string::npos)
      << r.err;
  std::ifstream config(std::filesystem::path(auto_out) / "config.yaml");
  std::ostringstream config_text;
  config_text << config.rdbuf();
  EXPECT_NE(config_text.str().find("from: the sensor's settings + preset indoor + --set"),
            std::string::npos)
      << config_text.str();
  // A sequence without ground truth: the error names what is missing.
  testing::WriteFile(dir / "seq" / "no_gt.yaml",
                     "calibration: calibration\nevents:\n  left: events/left/events.h5\n  right: "
                     "events/right/events.h5\n");
  r = RunAavio({"run", (dir / "seq" / "no_gt.yaml").string(), "--gt-poses", "--out", out});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("names no ground_truth.trajectory"), std::string::npos) << r.err;
}

// Adds `delay_ns` to every stamp of a TUM trajectory file (stamps written with 9 decimals).
void DelayGroundTruth(const std::filesystem::path& path, TimeNs delay_ns) {
  std::ifstream in(path);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t end = line.find(' ');
    if (line.empty() || line[0] == '#' || end == std::string::npos) {
      out << line << "\n";
      continue;
    }
    const std::string stamp = line.substr(0, end);
    const std::size_t dot = stamp.find('.');
    ASSERT_NE(dot, std::string::npos) << line;
    ASSERT_EQ(stamp.size() - dot - 1, 9u) << line;
    const TimeNs t_ns = std::stoll(stamp.substr(0, dot)) * 1'000'000'000 +
                        std::stoll(stamp.substr(dot + 1)) + delay_ns;
    out << FormatSecondsNs(t_ns) << line.substr(end) << "\n";
  }
  testing::WriteFile(path, out.str());
}

TEST(Cli, RunTracksAgainstGroundTruthMaps) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string(), out = (dir / "track").string();
  Result r =
      RunAavio({"simulate", "--preset", "mini", "--duration", "1.0", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  // The ground truth's first pose 0.5 µs after the first event, as a twin of a recorded path
  // with nanosecond stamps has it (its events are stamped in microseconds).
  DelayGroundTruth(std::filesystem::path(seq) / "groundtruth.txt", 500);
  // 160×120 px constrains translation weakly: the indoor preset's 5 cm divergence gate (for
  // 240×180) would count half of these ticks as lost; this test is about the mode.
  r = RunAavio({"run", seq, "--gt-map", "--out", out, "--preset", "indoor", "--quiet", "--set",
                "tracking.max_correction_m=0.3"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("RPE over 100 ms"), std::string::npos) << r.out;
  std::ifstream in(std::filesystem::path(out) / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_GT(j["poses"].get<int>(), 90);
  EXPECT_GT(j["status"]["ok"].get<int>(), 80);
  // The mini motion turns 4.0° and moves 2.6 cm per 100 ms (RMS); tracking at 160×120 px
  // (0.43° per pixel) follows the rotation to a fraction of that (measured 0.53°, 2.7 cm).
  EXPECT_LT(j["rpe_100ms"]["rotation_deg_rmse"].get<double>(), 1.0);
  EXPECT_LT(j["rpe_100ms"]["translation_m_rmse"].get<double>(), 0.04);
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "stamped_traj_estimate.txt"));
  // `aavio eval --run` works on this kind of run folder too.
  r = RunAavio({"eval", "--run", out, "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_GT(nlohmann::json::parse(r.out)["pairs"].get<int>(), 90);
}

using aavio::testing::ReadAll;

// The full odometry: its outputs, no NaN pose, and the same trajectory bit for bit with one and
// with two threads.
// Starting at rest: no map is made of the still camera's noise, the bootstrap retries every
// tick and says why, and the first map comes within 0.5 s of the motion's start.
TEST(Cli, RunBootstrapsWhenTheCameraStartsMoving) {
  const auto dir = testing::ScratchDir();
  // A camera path (TUM, the camera's own frame): 0.6 s still, then 0.3 m/s sideways while
  // turning at 0.4 rad/s.
  std::string path = "# t tx ty tz qx qy qz qw\n";
  for (int i = 0; i <= 400; ++i) {
    const double t = i / 200.0, moving = std::max(0.0, t - 0.6), yaw = 0.4 * moving;
    path += StrFormat("%.6f %.6f 0 0 0 %.6f 0 %.6f\n", 100.0 + t, 0.3 * moving, std::sin(yaw / 2),
                      std::cos(yaw / 2));
  }
  const std::string trajectory = testing::WriteFile(dir / "rest_then_move.txt", path);
  const std::string seq = (dir / "seq").string(), out = (dir / "run").string();
  Result r = RunAavio({"simulate", "--preset", "mini", "--trajectory", trajectory,
                       "--body-to-camera", "identity", "--duration", "2", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  r = RunAavio({"run", seq, "--out", out, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("found too few points and tried again"), std::string::npos) << r.out;
  std::ifstream in(std::filesystem::path(out) / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_TRUE(j["first_bootstrap_s"].is_number()) << j.dump();
  // When the camera starts to move: the simulator smooths the path's corner at 0.6 s, so the
  // ground truth says (its first 0.1 mm).
  double t_first = -1.0, t_moving = -1.0;
  Eigen::Vector3d p_first = Eigen::Vector3d::Zero();
  std::istringstream gt(ReadAll(std::filesystem::path(seq) / "groundtruth.txt"));
  for (std::string line; std::getline(gt, line) && t_moving < 0.0;) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    double t;
    Eigen::Vector3d p;
    fields >> t >> p.x() >> p.y() >> p.z();
    if (t_first < 0.0) t_first = t, p_first = p;
    if ((p - p_first).norm() > 1e-4) t_moving = t - t_first;
  }
  ASSERT_GT(t_moving, 0.4);
  // Nothing while still, and the first map within 0.5 s of the motion (measured 0.60 s; moving
  // from 0.59 s). Without the IMU's evidence of motion, a map of the still camera's noise came
  // at 0.53 s.
  EXPECT_GE(j["first_bootstrap_s"].get<double>(), t_moving);
  EXPECT_LE(j["first_bootstrap_s"].get<double>(), t_moving + 0.5);
  EXPECT_GT(j["bootstrap_failures"]["ticks"].get<int>(), 0);
  EXPECT_NE(j["bootstrap_failures"]["last_reason"].get<std::string>().find("min_points"),
            std::string::npos);
  // From the first map on, tracked (measured 139 of the 140 ticks after it, none lost).
  EXPECT_GE(j["status"]["ok"].get<int>(), 120) << j["status"].dump();
  EXPECT_EQ(j["reinitialisations"].get<int>(), 0);
}

// `aavio replay` plays the data at its own pace into the live odometry and accounts for every
// tick due (run or shed); played 50 times as fast, the odometry sheds ticks to keep up and says
// so.
TEST(Cli, ReplaySaysWhetherTheMachineKeepsUp) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string();
  Result r =
      RunAavio({"simulate", "--preset", "mini", "--duration", "1.5", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  // Every tick due, 1.5 s at 100 Hz, is run or shed — also those shed while the odometry
  // waited for the IMU sample past a tick (once lost from the count).
  for (const char* speed : {"1", "50"}) {
    r = RunAavio({"replay", seq, "--speed", speed});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    EXPECT_NE(r.out.find("pose latency"), std::string::npos) << r.out;
    long long run = -1, shed = -1;
    const std::size_t at = r.out.find("ticks: ");
    ASSERT_NE(at, std::string::npos) << r.out;
    ASSERT_EQ(std::sscanf(r.out.c_str() + at, "ticks: %lld run, %lld shed", &run, &shed), 2);
    EXPECT_EQ(run + shed, 150) << r.out;
    EXPECT_GT(run, 0) << r.out;
    if (std::string(speed) == "50") {
      EXPECT_GT(shed, 0) << r.out;
    }
  }
  r = RunAavio({"replay", seq, "--speed", "0"});
  EXPECT_EQ(r.code, kExitUsage) << r.err;
  r = RunAavio({"replay", seq, "--start", "5"});
  EXPECT_EQ(r.code, kExitUsage) << r.err;
  EXPECT_NE(r.err.find("--start is past the end"), std::string::npos) << r.err;
}

TEST(Cli, RunOdometryWritesItsOutputsAndIsDeterministic) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string();
  Result r =
      RunAavio({"simulate", "--preset", "mini", "--duration", "1.5", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::string one = (dir / "t1").string(), two = (dir / "t2").string();
  r = RunAavio({"run", seq, "--out", one, "--quiet", "--set", "pipeline.num_threads=1"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("accuracy vs ground truth"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("real-time factor"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("CPU-s per s of data"), std::string::npos) << r.out;
  r = RunAavio({"run", seq, "--out", two, "--quiet", "--set", "pipeline.num_threads=2"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::string traj = ReadAll(std::filesystem::path(one) / "stamped_traj_estimate.txt");
  EXPECT_EQ(traj, ReadAll(std::filesystem::path(two) / "stamped_traj_estimate.txt"));
  EXPECT_EQ(traj.find("nan"), std::string::npos);
  for (const char* name : {"summary.json", "timings.csv", "config.yaml", "map.ply"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(one) / name)) << name;
  for (const char* name :
       {"depth/timestamps.txt", "depth/disparity_000000.png", "depth/inverse_depth_000000.png"})
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(one) / name)) << name;
  std::ifstream in(std::filesystem::path(one) / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["mode"], "full");
  EXPECT_GE(j["poses"].get<int>(), 140);
  EXPECT_GT(j["status"]["ok"].get<int>(), 0);
  EXPECT_GE(j["bootstraps"].get<int>(), 1);
  // The mini twin moves from its first tick: the first map comes on the first mapping tick.
  ASSERT_TRUE(j["first_bootstrap_s"].is_number()) << j["first_bootstrap_s"];
  EXPECT_LT(j["first_bootstrap_s"].get<double>(), 0.5);
  for (const char* stage : {"event_reading", "event_insertion", "time_surface", "tracking",
                            "matching", "mapping_total"}) {
    EXPECT_TRUE(j["stages"].contains(stage)) << stage;
    EXPECT_GT(j["stages"][stage]["total_s"].get<double>(), 0.0) << stage;
  }
  EXPECT_GT(j["accuracy"]["pairs"].get<int>(), 100);
  EXPECT_GT(j["peak_rss_mb"].get<double>(), 0.0);
  // CPU time of every thread beside the real-time factor; a run's threads cannot use more than
  // the wall time on each of the cores they had.
  const double cpu_s = j["cpu_s"].get<double>(), data_s = j["data_duration_s"].get<double>();
  EXPECT_GT(cpu_s, 0.0);
  EXPECT_LE(cpu_s, j["wall_s"].get<double>() * std::thread::hardware_concurrency() + 0.05);
  EXPECT_NEAR(j["cpu_s_per_data_s"].get<double>(), cpu_s / data_s, 1e-9);
  EXPECT_GT(j["depth"]["points"].get<int>(), 0);
  // Per mapping cycle: what each kind of stereo matched, and where temporal candidates were lost
  // (their outcomes add up to the candidates).
  const nlohmann::json& per_cycle = j["mapping_per_cycle"];
  EXPECT_GT(j["mapping_cycles"].get<int>(), 10);
  EXPECT_GT(per_cycle["static_matches"].get<double>(), 0.0);
  EXPECT_GT(per_cycle["temporal_candidates"].get<double>(), 0.0);
  double outcomes = per_cycle["temporal_matches"].get<double>();
  for (const char* lost : {"temporal_no_segment", "temporal_no_match", "temporal_ill_conditioned",
                           "temporal_check_rejected", "temporal_out_of_range"})
    outcomes += per_cycle[lost].get<double>();
  EXPECT_NEAR(outcomes, per_cycle["temporal_candidates"].get<double>(), 1e-9);
  // Mapping inside each tick (no concurrent cycle): maps one tick earlier, so a different but
  // equally valid trajectory.
  r = RunAavio({"run", seq, "--out", two, "--quiet", "--overwrite", "--set",
                "pipeline.concurrent_mapping=false"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::string inline_traj = ReadAll(std::filesystem::path(two) / "stamped_traj_estimate.txt");
  EXPECT_EQ(inline_traj.find("nan"), std::string::npos);
  EXPECT_EQ(std::count(inline_traj.begin(), inline_traj.end(), '\n'),
            std::count(traj.begin(), traj.end(), '\n'));
  // ESVO-like mode: its configuration is the one that ran.
  r = RunAavio({"run", seq, "--out", two, "--quiet", "--overwrite", "--esvo"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::string config = ReadAll(std::filesystem::path(two) / "config.yaml");
  EXPECT_NE(config.find("mode: newest_events"), std::string::npos);
  EXPECT_NE(config.find("\n  mode: off\n"), std::string::npos);

  // `aavio eval --run` recomputes what the run reported, and scores its depth maps.
  r = RunAavio({"eval", "--run", one, "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json e = nlohmann::json::parse(r.out);
  for (const char* key : {"ate_rmse_m", "ate_mean_m", "ate_median_m", "ate_max_m", "pairs",
                          "path_length_m", "align", "rpe_trans_pct", "rpe_rot_deg_per_m", "rpe"})
    EXPECT_TRUE(e.contains(key)) << key;
  // (the run's trajectory file holds 9 decimals)
  EXPECT_NEAR(e["ate_rmse_m"].get<double>(), j["accuracy"]["ate_rmse_m"].get<double>(), 1e-7);
  EXPECT_EQ(e["rpe"].size(), 5u);
  // Velocities derived from both trajectories' poses, scored as EvSLAM does.
  EXPECT_GT(e["velocity"]["pairs"].get<int>(), 100);
  EXPECT_GT(e["velocity"]["auc"].get<double>(), 0.3);
  EXPECT_LE(e["velocity"]["auc"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(e["depth"]["relative"].get<double>(), j["depth"]["relative"].get<double>());
  EXPECT_LT(e["depth"]["relative"].get<double>(), 0.5);
  r = RunAavio({"eval", "--run", one});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("rpg_trajectory_evaluation form"), std::string::npos) << r.out;

  // Too little data for a score, or for a pose: an error, never a figure from two poses or a
  // run with no pose and exit 0; the outputs and summary.json are written all the same.
  const std::string short_run = (dir / "short").string();
  r = RunAavio({"run", seq, "--out", short_run, "--quiet", "--duration", "0.025"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("a trajectory score needs at least 10"), std::string::npos) << r.err;
  std::ifstream short_in(std::filesystem::path(short_run) / "summary.json");
  const nlohmann::json short_summary = nlohmann::json::parse(short_in);
  EXPECT_FALSE(short_summary.contains("accuracy"));
  EXPECT_NE(short_summary["accuracy_error"].get<std::string>().find("only 2 estimated pose(s)"),
            std::string::npos);
  r = RunAavio({"run", seq, "--out", short_run, "--quiet", "--overwrite", "--duration", "0.004"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("no pose was estimated"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--start and --duration"), std::string::npos) << r.err;
  // A run that never found a map (a depth range of 0.5-0.56 m, the scene at 1-5 m) holds the
  // start pose throughout: no estimate to score, with or without ground truth.
  const std::vector<std::string> no_map = {"--quiet",    "--overwrite",
                                           "--duration", "0.3",
                                           "--set",      "mapping.inv_depth_min=1.8",
                                           "--set",      "mapping.inv_depth_max=2"};
  std::vector<std::string> args = {"run", seq, "--out", short_run};
  args.insert(args.end(), no_map.begin(), no_map.end());
  r = RunAavio(args);
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("no tick of the 29 had a map: the odometry never found a first one"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the last attempt: SGM bootstrap found"), std::string::npos) << r.err;
  std::ifstream never_in(std::filesystem::path(short_run) / "summary.json");
  const nlohmann::json never_summary = nlohmann::json::parse(never_in);
  EXPECT_FALSE(never_summary.contains("accuracy"));
  EXPECT_EQ(never_summary["status"]["no_map"].get<int>(), 29);
  const std::string no_truth = testing::WriteFile(
      dir / "no_truth" / "sequence.yaml",
      "calibration: " + seq + "/calibration\nevents:\n  left: " + seq +
          "/events/left/events.h5\n  right: " + seq + "/events/right/events.h5\n");
  args = {"run", no_truth, "--out", short_run};
  args.insert(args.end(), no_map.begin(), no_map.end());
  r = RunAavio(args);
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("no tick of the 29 had a map"), std::string::npos) << r.err;

  // `aavio report` of the two runs on one page: one html file with every figure embedded, and
  // nothing left behind (its working folder is a temporary one).
  const std::filesystem::path report_dir = dir / "report", scratch = dir / "tmp";
  std::filesystem::create_directories(scratch);
  const char* old_tmpdir = std::getenv("TMPDIR");
  const std::string saved_tmpdir = old_tmpdir ? old_tmpdir : "";
  setenv("TMPDIR", scratch.c_str(), 1);
  const std::string html = (report_dir / "report.html").string();
  r = RunAavio(
      {"report", "--run", one, "--run", two, "--name", "full", "--name", "esvo", "--out", html});
  if (old_tmpdir)
    setenv("TMPDIR", saved_tmpdir.c_str(), 1);
  else
    unsetenv("TMPDIR");
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::string page = ReadAll(html);
  std::size_t images = 0;
  for (std::size_t at = page.find("data:image/png;base64,"); at != std::string::npos;
       at = page.find("data:image/png;base64,", at + 1))
    ++images;
  // Views, error along the path, against time, over distance, velocity, two runs' depth maps,
  // depth errors, map from above, strips, timing.
  EXPECT_GE(images, 11u) << page.substr(0, 3000);
  for (const char* caption :
       {"error of each pose along the path", "Position and orientation against time",
        "error of the velocity", "depth maps as written to depth/", "by the kind of edge",
        "coloured by height", "against the real-time budget", "Configuration differences",
        "edge_sampling.mode"})
    EXPECT_NE(page.find(caption), std::string::npos) << caption;
  EXPECT_EQ(page.find("src=\"file:"), std::string::npos);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(report_dir),
                          std::filesystem::directory_iterator{}),
            1);
  EXPECT_TRUE(std::filesystem::is_empty(scratch));
  // timings.csv counts each tick's events (the strips' event rate) and the IMU's estimates.
  EXPECT_NE(ReadAll(std::filesystem::path(one) / "timings.csv")
                .find(",lost_reason,events,gyro_bias_x,gyro_bias_y,gyro_bias_z,accel_bias_x,"),
            std::string::npos);
  // Real-time mode: mapping on its own thread; it runs, maps and tracks (not bit-reproducible).
  const std::string rt = (dir / "rt").string();
  r = RunAavio({"run", seq, "--out", rt, "--quiet", "--real-time"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  std::ifstream rt_in(std::filesystem::path(rt) / "summary.json");
  const nlohmann::json rj = nlohmann::json::parse(rt_in);
  EXPECT_TRUE(rj["real_time_mode"].get<bool>());
  EXPECT_GT(rj["status"]["ok"].get<int>(), 0);
  EXPECT_GT(rj["stages"]["mapping_total"]["calls"].get<int>(), 0);
  EXPECT_EQ(ReadAll(std::filesystem::path(rt) / "stamped_traj_estimate.txt").find("nan"),
            std::string::npos);
  // Both isolation modes at once: a usage error.
  r = RunAavio({"run", seq, "--out", two, "--gt-map", "--gt-poses"});
  EXPECT_EQ(r.code, kExitUsage);
}

// README's path for a bag: `aavio run X.bag --calib DIR`, then `aavio eval --run` scores it
// against the bag's own ground-truth pose topic with the calibration the run recorded.
// --world gravity: the trajectory and map.ply of the same run, turned z-up by the gravity it
// measured (needs 2 s of data); the summary says which world the files are in.
TEST(Cli, RunWritesAGravityAlignedWorldOnRequest) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string();
  Result r =
      RunAavio({"simulate", "--preset", "mini", "--duration", "2.6", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::filesystem::path camera = dir / "camera", gravity = dir / "gravity";
  r = RunAavio({"run", seq, "--out", camera.string(), "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  r = RunAavio({"run", seq, "--out", gravity.string(), "--quiet", "--world", "gravity"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("world: z up along the measured gravity"), std::string::npos) << r.out;
  auto summary = [](const std::filesystem::path& run) {
    std::ifstream in(run / "summary.json");
    return nlohmann::json::parse(in);
  };
  const nlohmann::json a = summary(camera), b = summary(gravity);
  EXPECT_EQ(a["world"]["frame"], "first_camera");
  ASSERT_EQ(b["world"]["frame"], "gravity") << b["world"];
  const auto& q = b["world"]["q_world_first_camera_xyzw"];
  const Eigen::Matrix3d R = Eigen::Quaterniond(q[3].get<double>(), q[0].get<double>(),
                                               q[1].get<double>(), q[2].get<double>())
                                .toRotationMatrix();
  // The same rotation the first-camera run's summary gives, and gravity now straight down.
  const auto& q_up = a["motion"]["gravity"]["q_up_world_xyzw"];
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR(q[k].get<double>(), q_up[k].get<double>(), 1e-12);
  EXPECT_NEAR(b["motion"]["gravity"]["down_world"][2].get<double>(), -1.0, 1e-9);
  // The simulated camera starts with y towards the ground.
  EXPECT_GT((R * Eigen::Vector3d::UnitY()).dot(-Eigen::Vector3d::UnitZ()), 0.99);
  Expected<std::vector<geometry::StampedPose>> p =
      io::ReadTumTrajectory((camera / "stamped_traj_estimate.txt").string());
  Expected<std::vector<geometry::StampedPose>> p_up =
      io::ReadTumTrajectory((gravity / "stamped_traj_estimate.txt").string());
  ASSERT_TRUE(p && p_up);
  ASSERT_EQ(p->size(), p_up->size());
  for (std::size_t i = 0; i < p->size(); ++i) {
    EXPECT_LT((R * (*p)[i].T_world_body.t - (*p_up)[i].T_world_body.t).norm(), 1e-6) << i;
    EXPECT_LT((R * (*p)[i].T_world_body.R - (*p_up)[i].T_world_body.R).norm(), 1e-6) << i;
  }
  Expected<recording::ColouredCloud> cloud = recording::ReadPly((camera / "map.ply").string());
  Expected<recording::ColouredCloud> cloud_up = recording::ReadPly((gravity / "map.ply").string());
  ASSERT_TRUE(cloud && cloud_up);
  ASSERT_EQ(cloud->points.size(), cloud_up->points.size());
  ASSERT_GT(cloud->points.size(), 100u);
  for (std::size_t i = 0; i < cloud->points.size(); i += 97) {
    const Eigen::Vector3d turned = R * cloud->points[i].cast<double>();
    EXPECT_LT((turned - cloud_up->points[i].cast<double>()).norm(), 1e-4) << i;
  }
  // The error is the same (se3-aligned); with --gt-poses the world is the ground truth's.
  EXPECT_NEAR(a["accuracy"]["ate_rmse_m"].get<double>(), b["accuracy"]["ate_rmse_m"].get<double>(),
              1e-9);
  r = RunAavio({"run", seq, "--out", (dir / "gt").string(), "--gt-poses", "--world", "gravity"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("the run's world is the ground truth's"), std::string::npos) << r.err;
}

TEST(Cli, EvalScoresABagRunWithItsCalibrationAndTheBagsPoses) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string();
  Result r = RunAavio({"simulate", "--preset", "mini", "--duration", "1", "--format", "bag",
                       "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::filesystem::path calib = dir / "calib";
  std::filesystem::rename(std::filesystem::path(seq) / "calibration", calib);
  const std::string bag = (std::filesystem::path(seq) / "events.bag").string();
  const std::string out = (dir / "run").string();
  r = RunAavio({"run", bag, "--calib", calib.string(), "--out", out, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("accuracy vs ground truth"), std::string::npos) << r.out;
  std::ifstream in(std::filesystem::path(out) / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["calibration"].get<std::string>(),
            std::filesystem::absolute(calib).lexically_normal().string());
  r = RunAavio({"eval", "--run", out, "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json e = nlohmann::json::parse(r.out);
  EXPECT_EQ(e["ground_truth"].get<std::string>(), bag);
  EXPECT_NEAR(e["ate_rmse_m"].get<double>(), summary["accuracy"]["ate_rmse_m"].get<double>(), 1e-7);
  // The calibration moved: the run's record no longer helps; --calib names it again.
  const std::filesystem::path moved = dir / "calib_moved";
  std::filesystem::rename(calib, moved);
  r = RunAavio({"eval", "--run", out});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("give one with --calib"), std::string::npos) << r.err;
  r = RunAavio({"eval", "--run", out, "--calib", moved.string()});
  EXPECT_EQ(r.code, kExitOk) << r.err;

  // EvSLAM's submission: poses and camera-frame velocities at given stamps (here every other
  // ground-truth stamp, and two outside the run), which aavio eval reads back.
  std::string stamps = "0.0\n";
  const std::string gt = ReadAll(std::filesystem::path(seq) / "groundtruth.txt");
  std::istringstream lines(gt);
  std::string line;
  int n = 0;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] != '#' && n++ % 2 == 1)
      stamps += line.substr(0, line.find(' ')) + "\n";
  stamps += "100.0\n";
  const std::string stamps_path = testing::WriteFile(dir / "ref_time.txt", stamps);
  const std::string evslam = (dir / "evslam").string();
  r = RunAavio({"run", bag, "--calib", moved.string(), "--out", evslam, "--quiet", "--format",
                "evslam", "--poses-at", stamps_path});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("trajectory_evslam.txt: "), std::string::npos) << r.out;
  std::ifstream evslam_in(std::filesystem::path(evslam) / "summary.json");
  const nlohmann::json motion = nlohmann::json::parse(evslam_in)["motion"];
  EXPECT_EQ(motion["poses_at"]["missing"].get<int>(), 2) << motion.dump();
  EXPECT_GT(motion["speed_median_mps"].get<double>(), 0.05);
  const std::string file = (std::filesystem::path(evslam) / "trajectory_evslam.txt").string();
  const std::string written = ReadAll(file);
  EXPECT_EQ(std::count(written.begin(), written.end(), '\n'),
            motion["poses_at"]["written"].get<int>() + 1);  // + the header
  const std::string gt_path = (std::filesystem::path(seq) / "groundtruth.txt").string();
  r = RunAavio({"eval", "--est", file, "--gt", gt_path, "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  // The file's own velocities are scored.
  EXPECT_EQ(nlohmann::json::parse(r.out)["velocity"]["estimate"], "given") << r.out;
  // KITTI out and in: with its times file the same score as the run's own TUM trajectory.
  const std::string kitti = (dir / "kitti").string();
  r = RunAavio(
      {"run", bag, "--calib", moved.string(), "--out", kitti, "--quiet", "--format", "kitti"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto kitti_dir = std::filesystem::path(kitti);
  r = RunAavio({"eval", "--est", (kitti_dir / "trajectory_kitti.txt").string(), "--gt", gt_path,
                "--times", (kitti_dir / "trajectory_kitti_times.txt").string(), "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  std::ifstream kitti_in(kitti_dir / "summary.json");
  EXPECT_NEAR(nlohmann::json::parse(r.out)["ate_rmse_m"].get<double>(),
              nlohmann::json::parse(kitti_in)["accuracy"]["ate_rmse_m"].get<double>(), 1e-6);
  r = RunAavio({"eval", "--est", (kitti_dir / "trajectory_kitti.txt").string(), "--gt", gt_path});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("give its times.txt with --times"), std::string::npos) << r.err;
  // Both runs in one table (evo_res's), as CSV: a row each, the same ATE (same data, same seed).
  r = RunAavio({"eval", "--run", out, "--run", evslam, "--calib", moved.string(), "--name", "one",
                "--name", "two", "--table", "csv"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(r.out.find("run,ATE [m],ATE [%]"), 0u) << r.out;
  const std::size_t one = r.out.find("\none,"), two = r.out.find("\ntwo,");
  ASSERT_NE(one, std::string::npos) << r.out;
  ASSERT_NE(two, std::string::npos) << r.out;
  EXPECT_EQ(r.out.substr(one + 5, 7), r.out.substr(two + 5, 7)) << r.out;
  r = RunAavio({"eval", "--run", out, "--run", evslam, "--name", "one"});
  EXPECT_EQ(r.code, kExitUsage);
  r = RunAavio(
      {"run", bag, "--calib", moved.string(), "--out", evslam, "--overwrite", "--format", "g2o"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("none of tum, tum_ns, kitti, euroc, evslam"), std::string::npos) << r.err;
  // A summary.json edited by hand: entries of the wrong type are read as missing, never a crash.
  testing::WriteFile(std::filesystem::path(out) / "summary.json",
                     "{\"sequence\": \"" + bag + "\", \"calibration\": \"" + moved.string() +
                         "\", \"motion\": {\"gravity\": {\"q_up_world_xyzw\": [\"a\", 1, "
                         "2, 3]}}, \"status\": 5, \"real_time_factor\": \"x\"}");
  r = RunAavio({"eval", "--run", out, "--align", "posyaw"});
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("no measured gravity"), std::string::npos) << r.out;
  r = RunAavio({"eval", "--run", out, "--run", evslam});
  EXPECT_EQ(r.code, kExitOk) << r.err;
}

}  // namespace
}  // namespace aavio::cli
