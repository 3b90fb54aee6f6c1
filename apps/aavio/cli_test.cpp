#include "cli.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "aavio/common/format.hpp"
#include "tests/event_fixtures.hpp"
#include "tests/fixtures/calibrations.hpp"
#include "tests/test_utils.hpp"

namespace aavio::cli {
namespace {

struct Result {
  int code;
  std::string out, err;
};

Result RunAavio(const std::vector<std::string>& args) {
  std::vector<std::string> argv;
  argv.reserve(args.size() + 1);
  argv.emplace_back("aavio");
  for (const std::string& arg : args)
    argv.push_back(arg);
  std::ostringstream out, err;
  const int code = RunCli(argv, out, err);
  return {code, out.str(), err.str()};
}

std::string RpgDir() {
  const auto dir = testing::ScratchDir();
  testing::WriteFile(dir / "left.yaml", testing::kRpgLeftYaml);
  testing::WriteFile(dir / "right.yaml", testing::kRpgRightYaml);
  return dir.string();
}

TEST(Cli, VersionAndHelp) {
  Result r = RunAavio({"--version"});
  EXPECT_EQ(r.code, kExitOk);
  EXPECT_EQ(r.out.rfind("aavio 0.", 0), 0u);
  r = RunAavio({"--help"});
  EXPECT_EQ(r.code, kExitOk);
  for (const char* command : {"simulate", "run", "eval", "demo", "info", "report", "config"}) {
    EXPECT_NE(r.out.find(command), std::string::npos) << command;
  }
  r = RunAavio({"info", "--help"});
  EXPECT_EQ(r.code, kExitOk);
  EXPECT_NE(r.out.find("--json"), std::string::npos);
}

TEST(Cli, UsageErrors) {
  Result r = RunAavio({"frobnicate"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("aavio --help"), std::string::npos);
  EXPECT_EQ(RunAavio({"info"}).code, kExitUsage);  // path is required
  EXPECT_EQ(RunAavio({}).code, kExitUsage);
}

TEST(Cli, InfoDescribesACalibration) {
  const std::string dir = RpgDir();
  Result r = RunAavio({"info", dir});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("240 x 180 px"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("f 156.925 px"), std::string::npos);
  EXPECT_NE(r.out.find("baseline         0.1480 m"), std::string::npos);
  EXPECT_NE(r.out.find("plumb_bob"), std::string::npos);
  r = RunAavio({"info", dir, "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["rectified"]["baseline_m"].get<double>(), 0.14805, 1e-5);
  EXPECT_EQ(j["left"]["distortion_model"], "plumb_bob");
  EXPECT_GT(j["rectified"]["valid_share_left"].get<double>(), 0.8);
  EXPECT_FALSE(j["T_imu_left"].is_null());
}

TEST(Cli, InfoReportsBadInputWithoutCrashing) {
  Result r = RunAavio({"info", "/nonexistent/calib"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("aavio info: error: /nonexistent/calib: no such file"), std::string::npos);
  const auto dir = testing::ScratchDir();
  testing::WriteFile(dir / "left.yaml", "image_width: [\n");
  testing::WriteFile(dir / "right.yaml", testing::kRpgRightYaml);
  r = RunAavio({"info", dir.string()});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("YAML syntax error"), std::string::npos);
}

TEST(Cli, InfoDescribesDataFiles) {
  Result r = RunAavio({"info", testing::Fixture("dsec_blosc.h5")});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("200000 events, 36470.123457000 .. 36470.373456000 s"), std::string::npos)
      << r.out;
  r = RunAavio({"info", testing::Fixture("bag_lz4.bag"), "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["kind"], "bag");
  EXPECT_EQ(j["/davis/left/events"]["events"], 20000);
  EXPECT_EQ(j["/davis/right/events"]["events"], 15000);
  EXPECT_EQ(j["/davis/left/events"]["resolution"], nlohmann::json({240, 180}));
  EXPECT_NEAR(j["imu"]["rate_hz"].get<double>(), 1000.0, 1e-6);
  EXPECT_EQ(j["topics"]["/gt/pose"]["type"], "geometry_msgs/PoseStamped");
  r = RunAavio({"info", testing::Fixture("backwards.h5")});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("goes back 30.000 ms"), std::string::npos) << r.err;
}

TEST(Cli, ConvertRoundTripsThroughEveryFormat) {
  const auto dir = testing::ScratchDir();
  testing::WriteFile(dir / "calib" / "left.yaml", testing::kRpgLeftYaml);
  testing::WriteFile(dir / "calib" / "right.yaml", testing::kRpgRightYaml);
  std::string from = testing::Fixture("bag_bz2.bag");
  std::vector<std::string> extra = {"--calib", (dir / "calib").string()};
  for (const char* format : {"h5", "txt", "bag"}) {
    const std::string out = (dir / format).string();
    std::vector<std::string> args = {"convert", from, "--to", format, "--out", out};
    args.insert(args.end(), extra.begin(), extra.end());
    Result r = RunAavio(args);
    ASSERT_EQ(r.code, kExitOk) << format << ": " << r.err;
    EXPECT_NE(r.out.find("converted 20000 left + 15000 right events and 200 IMU samples"),
              std::string::npos)
        << r.out;
    r = RunAavio({"info", out, "--json"});
    ASSERT_EQ(r.code, kExitOk) << format << ": " << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["left"]["events"], 20000) << format;
    EXPECT_EQ(j["right"]["events"], 15000) << format;
    EXPECT_EQ(j["ground_truth"]["poses"], 20) << format;
    // Timestamps survive every hop (h5 stores µs: the fixture's ns are rounded once).
    EXPECT_EQ(j["left"]["t_first_s"], "36470.123466000") << format;
    from = out;  // the next hop starts from this one's sequence.yaml
    extra.clear();
  }
}

TEST(Cli, ConfigPrintsListsAndWritesTheEffectiveConfig) {
  Result r = RunAavio({"config", "--preset", "indoor", "--set", "mapping.eta=0.15"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("from: preset indoor + --set mapping.eta=0.15"), std::string::npos);
  EXPECT_NE(r.out.find("  eta: 0.15\n"), std::string::npos);
  EXPECT_NE(r.out.find("  inv_depth_max: 2.0\n"), std::string::npos);

  const auto dir = testing::ScratchDir();
  const std::string written = (dir / "config.yaml").string();
  ASSERT_EQ(RunAavio({"config", "--preset", "driving", "--out", written}).code, kExitOk);
  // The written file is a complete config: loading it alone reproduces the same output.
  Result a = RunAavio({"config", "--preset", "driving"});
  Result b = RunAavio({"config", "--config", written});
  auto body = [](const std::string& s) { return s.substr(s.find("\n", s.find("from:")) + 1); };
  EXPECT_EQ(body(a.out), body(b.out));

  r = RunAavio({"config", "--list"});
  EXPECT_NE(r.out.find("mapping.fusion.strategy"), std::string::npos);
  EXPECT_NE(r.out.find("one of const_frames|const_points"), std::string::npos);
  // Each key with its value, type, the rule Validate() applies and a description.
  EXPECT_NE(r.out.find("number, must be in [0.1, 10000]\n    exponential decay"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("mapping.eta"), std::string::npos);
  EXPECT_NE(r.out.find("number, must be >= 0\n    η: |g_u| / |g_v|"), std::string::npos);
}

// Every overlay under configs/overlays loads on top of the driving preset and sets what it says.
TEST(Cli, OverlaysApplyOnTopOfThePreset) {
  const std::filesystem::path overlays =
      std::filesystem::path(AAVIO_SOURCE_DIR) / "configs/overlays";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(overlays)) {
    SCOPED_TRACE(entry.path().string());
    const Result r = RunAavio({"config", "--preset", "driving", "--config", entry.path().string()});
    EXPECT_EQ(r.code, kExitOk) << r.err;
    ++count;
  }
  EXPECT_GE(count, 1);
  const Result r =
      RunAavio({"config", "--preset", "driving", "--config", (overlays / "esvo.yaml").string()});
  EXPECT_NE(r.out.find("  mode: newest_events\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("    enabled: false\n"), std::string::npos);
  EXPECT_NE(r.out.find("  eta: 0.2\n"), std::string::npos);  // the preset's, untouched
  // By name: the overlay embedded in the binary, the same configuration.
  const Result by_name = RunAavio({"config", "--preset", "driving", "--config", "esvo"});
  EXPECT_EQ(by_name.code, kExitOk) << by_name.err;
  auto body = [](const std::string& out) { return out.substr(out.find("\n\npipeline:")); };
  EXPECT_EQ(body(by_name.out), body(r.out));
  EXPECT_NE(by_name.out.find("# from: preset driving + esvo\n"), std::string::npos);
  const Result unknown = RunAavio({"config", "--config", "esvo2"});
  EXPECT_EQ(unknown.code, kExitError);
  EXPECT_NE(unknown.err.find("esvo2"), std::string::npos) << unknown.err;
}

TEST(Cli, ConfigErrorsAreClear) {
  Result r = RunAavio({"config", "--set", "mapping.etta=0.1"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("did you mean 'mapping.eta'"), std::string::npos) << r.err;
  r = RunAavio({"config", "--set", "mapping.eta=-1"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("invalid configuration: mapping.eta = -1 must be >= 0"), std::string::npos)
      << r.err;
  r = RunAavio({"config", "--preset", "kitti"});
  EXPECT_NE(r.err.find("no preset named 'kitti'"), std::string::npos);
  r = RunAavio({"config", "--config", "/nonexistent.yaml"});
  EXPECT_NE(r.err.find("/nonexistent.yaml: no such file"), std::string::npos);
}

}  // namespace
}  // namespace aavio::cli

namespace aavio::cli {
namespace {

// `config --for`: the sensor's settings of a sequence's rig, each with its rule, the preset the
// rig suggests and why, and which settings a later source changes.
TEST(Cli, ConfigForASequenceDerivesTheSensorsSettings) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string();
  Result r =
      RunAavio({"simulate", "--preset", "mini", "--duration", "0.2", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  r = RunAavio({"config", "--for", seq, "--set", "edge_sampling.num_points=2400"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("# sensor: 160 x 120 px, f "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("# preset: indoor (baseline 0.15 m < 0.3 m"), std::string::npos) << r.out;
  // 160×120: the paper's 8 blocks across, square ones down; 4 × 3 sampling blocks at least.
  EXPECT_NE(r.out.find("#   adaptive_accumulation.grid_rows"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  grid_rows: 6\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[a later source sets 2400]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  num_points: 2400\n"), std::string::npos) << r.out;
  // A named preset is kept; the calibration alone is enough.
  r = RunAavio({"config", "--for", (std::filesystem::path(seq) / "calibration").string(),
                "--preset", "driving"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("# preset: driving (named)"), std::string::npos) << r.out;
  r = RunAavio({"config", "--for", (dir / "nothing").string()});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("--for " + (dir / "nothing").string() + ": neither a calibration"),
            std::string::npos)
      << r.err;
  // The former dataset names say what they became.
  r = RunAavio({"config", "--preset", "rpg"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("rpg became indoor"), std::string::npos) << r.err;
}

TEST(Cli, RepresentationsOfASimulatedTick) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string(), out = (dir / "rep").string();
  Result r = RunAavio({"simulate", "--preset", "mini", "--duration", "1", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  r = RunAavio({"representations", seq, "--at", "0.5", "--out", out, "--preset", "indoor", "--set",
                "edge_sampling.num_points=300", "--set", "mapping.max_points=300"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("samples: 300 from AA (budget 300)"), std::string::npos) << r.out;
  for (const char* name : {"ts_left.png", "ts_right.png", "negative_ts_left.png", "gradient_u.png",
                           "aa_map.png", "aa_blocks_raw.png", "samples.png", "samples_esvo.png"}) {
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / name)) << name;
  }
  // A tick outside the sequence, and a path that is not a sequence: clear errors.
  r = RunAavio({"representations", seq, "--at", "7", "--out", out});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("--at 7.000 is outside the sequence (0 to 1.0"), std::string::npos) << r.err;
  r = RunAavio({"representations", (dir / "nothing").string(), "--at", "0", "--out", out});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("nothing"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace aavio::cli

namespace aavio::cli {
namespace {

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

}  // namespace
}  // namespace aavio::cli

namespace aavio::cli {
namespace {

TEST(Cli, RunTracksAgainstGroundTruthMaps) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string(), out = (dir / "track").string();
  Result r =
      RunAavio({"simulate", "--preset", "mini", "--duration", "1.0", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
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

}  // namespace
}  // namespace aavio::cli

namespace aavio::cli {
namespace {

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text, line;
  while (std::getline(in, line))
    text += line + "\n";
  return text;
}

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
  EXPECT_GE(j["first_bootstrap_s"].get<double>(), 0.55);  // nothing while still (measured 0.60)
  EXPECT_LE(j["first_bootstrap_s"].get<double>(), 1.1);
  EXPECT_GT(j["bootstrap_failures"]["ticks"].get<int>(), 0);
  EXPECT_NE(j["bootstrap_failures"]["last_reason"].get<std::string>().find("min_points"),
            std::string::npos);
  // From the first map on, tracked (measured 139 of the 140 ticks after it, none lost).
  EXPECT_GE(j["status"]["ok"].get<int>(), 120) << j["status"].dump();
  EXPECT_EQ(j["reinitialisations"].get<int>(), 0);
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
  EXPECT_DOUBLE_EQ(e["depth"]["relative"].get<double>(), j["depth"]["relative"].get<double>());
  EXPECT_LT(e["depth"]["relative"].get<double>(), 0.5);
  r = RunAavio({"eval", "--run", one});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("rpg_trajectory_evaluation form"), std::string::npos) << r.out;

  // `aavio report` of the two runs on one page: html with the plots embedded, non-empty PNGs.
  const std::string html = (dir / "report" / "report.html").string();
  r = RunAavio(
      {"report", "--run", one, "--run", two, "--name", "full", "--name", "esvo", "--out", html});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::string page = ReadAll(html);
  EXPECT_NE(page.find("data:image/png;base64,"), std::string::npos);
  EXPECT_NE(page.find("esvo"), std::string::npos);
  EXPECT_NE(page.find("over the time surface"), std::string::npos);
  // timings.csv counts each tick's events (the strips' event rate).
  EXPECT_NE(ReadAll(std::filesystem::path(one) / "timings.csv").find(",lost_reason,events\n"),
            std::string::npos);
  for (const char* png : {"trajectory.png", "errors_over_distance.png", "depth_error.png",
                          "timing.png", "depth_maps.png", "map_from_above.png", "strips.png"}) {
    const auto path = dir / "report" / "report_files" / png;
    ASSERT_TRUE(std::filesystem::exists(path)) << png;
    EXPECT_GT(std::filesystem::file_size(path), 5000u) << png;
  }
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

// `aavio eval --est --gt`: a rigidly moved copy has no error with se3 but has without alignment;
// bad arguments and non-overlapping trajectories are clear errors.
TEST(Cli, EvalComparesTrajectoryFiles) {
  const auto dir = testing::ScratchDir();
  std::string gt = "# timestamp tx ty tz qx qy qz qw\n", moved = gt, late = gt;
  for (int i = 0; i < 200; ++i) {
    const double t = 100.0 + 0.01 * i, s = 0.02 * i;
    // moved = a yaw of 90 degrees and a shift: (x, y, z) -> (-y + 1, x - 2, z + 0.5)
    const double x = std::cos(s), y = std::sin(1.5 * s), z = 0.1 * s;
    gt += StrFormat("%.9f %.9f %.9f %.9f 0 0 0 1\n", t, x, y, z);
    moved += StrFormat("%.9f %.9f %.9f %.9f 0 0 0.7071067811865476 0.7071067811865476\n", t,
                       -y + 1.0, x - 2.0, z + 0.5);
    late += StrFormat("%.9f %.9f %.9f %.9f 0 0 0 1\n", t + 50.0, x, y, z);
  }
  testing::WriteFile(dir / "gt.txt", gt);
  testing::WriteFile(dir / "moved.txt", moved);
  testing::WriteFile(dir / "late.txt", late);
  const std::string g = (dir / "gt.txt").string(), m = (dir / "moved.txt").string();
  for (const char* align : {"se3", "posyaw", "sim3"}) {
    const Result r = RunAavio({"eval", "--est", m, "--gt", g, "--align", align, "--json"});
    ASSERT_EQ(r.code, kExitOk) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_LT(j["ate_rmse_m"].get<double>(), 1e-6) << align;
    EXPECT_LT(j["rpe_trans_pct"].get<double>(), 1e-4) << align;
    EXPECT_EQ(j["pairs"].get<int>(), 200);
  }
  Result r = RunAavio({"eval", "--est", m, "--gt", g, "--align", "none", "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_GT(nlohmann::json::parse(r.out)["ate_rmse_m"].get<double>(), 1.0);
  r = RunAavio({"eval", "--est", m, "--gt", g, "--lengths", "0.5,1"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("      0.50"), std::string::npos) << r.out;
  r = RunAavio({"eval", "--est", m, "--gt", g, "--align", "affine"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("posyaw"), std::string::npos) << r.err;
  r = RunAavio({"eval", "--est", (dir / "late.txt").string(), "--gt", g});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("overlap"), std::string::npos) << r.err;
  EXPECT_EQ(RunAavio({"eval", "--est", m}).code, kExitUsage);
  EXPECT_EQ(RunAavio({"eval", "--est", m, "--gt", g, "--run", dir.string()}).code, kExitUsage);
  r = RunAavio({"eval", "--run", dir.string()});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("summary.json"), std::string::npos) << r.err;
}

TEST(Cli, SimulateTakesASensorLevelOrFileAndSaysWhatItIs) {
  const auto dir = testing::ScratchDir();
  const std::string seq = (dir / "seq").string();
  Result r =
      RunAavio({"simulate", "--preset", "mini", "--duration", "0.3", "--out", seq, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("sensor typical"), std::string::npos) << r.out;
  // The odometry's calibration carries the typical calibration error; the truth is kept beside.
  EXPECT_TRUE(
      std::filesystem::exists(std::filesystem::path(seq) / "calibration_true" / "left.yaml"));
  r = RunAavio({"info", (std::filesystem::path(seq) / "calibration").string(), "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json told = nlohmann::json::parse(r.out);
  r = RunAavio({"info", (std::filesystem::path(seq) / "calibration_true").string(), "--json"});
  const nlohmann::json truth = nlohmann::json::parse(r.out);
  EXPECT_NE(told["left"]["cx"].get<double>(), truth["left"]["cx"].get<double>());
  // --stats on the simulated events.
  r = RunAavio({"info", "--stats",
                (std::filesystem::path(seq) / "events" / "left" / "events.h5").string(), "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const nlohmann::json stats = nlohmann::json::parse(r.out)["events"]["stats"];
  EXPECT_GT(stats["on_fraction"].get<double>(), 0.3);
  EXPECT_LT(stats["on_fraction"].get<double>(), 0.6);
  EXPECT_GT(stats["events_per_passage"].get<double>(), 1.0);

  // The printed sensor is a sensor file; one effect alone; bad names and values.
  r = RunAavio({"simulate", "--preset", "mini", "--sensor", "harsh", "--print-sensor"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const std::string file = (dir / "harsh.yaml").string();
  std::ofstream(file) << r.out;
  r = RunAavio({"simulate", "--preset", "mini", "--duration", "0.2", "--out", (dir / "f").string(),
                "--sensor", file, "--effects", "jitter,calibration", "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("harsh.yaml: jitter, calibration"), std::string::npos) << r.out;
  r = RunAavio(
      {"simulate", "--preset", "mini", "--out", (dir / "g").string(), "--sensor", "noisy"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("use ideal, typical, harsh or a sensor YAML file"), std::string::npos);
  r = RunAavio({"simulate", "--preset", "mini", "--out", (dir / "g").string(), "--duration", "-1"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("--duration: Value -1 not in range [0.001, 86400]"), std::string::npos)
      << r.err;
}

TEST(Cli, DemoSimulatesRunsAndReportsAccuracy) {
  const auto dir = testing::ScratchDir();
  const Result r = RunAavio({"demo", "--out", (dir / "demo").string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("ATE RMSE"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("demo done"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "demo" / "run" / "stamped_traj_estimate.txt"));
}

}  // namespace
}  // namespace aavio::cli
