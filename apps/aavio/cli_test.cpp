#include "cli.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "aavio/common/format.hpp"
#include "cli_test_util.hpp"
#include "tests/event_fixtures.hpp"
#include "tests/fixtures/calibrations.hpp"
#include "tests/test_utils.hpp"

namespace aavio::cli {
namespace {

using testing_cli::Result;
using testing_cli::RunAavio;

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

// A text file is told apart by its columns: events, an IMU or a TUM trajectory; anything else
// is named with the three forms.
TEST(Cli, InfoTellsTextFilesApartByTheirColumns) {
  const auto dir = testing::ScratchDir();
  testing::WriteFile(dir / "events.txt", "0.001 10 20 1\n0.002 11 20 0\n");
  testing::WriteFile(dir / "imu.txt",
                     "# t ax ay az gx gy gz\n0.000 0 9.81 0 0.1 0 0\n"
                     "0.001 0 9.81 0 0.1 0 0\n0.002 0 9.81 0 0.1 0 0\n");
  testing::WriteFile(dir / "groundtruth.txt",
                     "# timestamp tx ty tz qx qy qz qw\n"
                     "0.0 0 0 0 0 0 0 1\n0.1 0.3 0 0 0 0 0 1\n"
                     "0.2 0.3 0.4 0 0 0 0 1\n");
  testing::WriteFile(dir / "groundtruth_ns.txt",
                     "0,0,0,0,0,0,0,1\n100000000,0.3,0,0,0,0,0,1\n"
                     "200000000,0.3,0.4,0,0,0,0,1\n");
  testing::WriteFile(dir / "odd.txt", "1 2 3 4 5\n");
  Result r = RunAavio({"info", (dir / "events.txt").string(), "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["kind"], "events");
  r = RunAavio({"info", (dir / "imu.txt").string(), "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["kind"], "imu");
  EXPECT_EQ(j["imu"]["samples"], 3);
  r = RunAavio({"info", (dir / "groundtruth.txt").string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("3 poses at 10.0 Hz, 0.000000000 .. 0.200000000 s, path 0.700 m"),
            std::string::npos)
      << r.out;
  // Comma-separated, nanosecond stamps: the same trajectory.
  r = RunAavio({"info", (dir / "groundtruth_ns.txt").string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("3 poses at 10.0 Hz, 0.000000000 .. 0.200000000 s, path 0.700 m"),
            std::string::npos)
      << r.out;
  r = RunAavio({"info", (dir / "odd.txt").string()});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("odd.txt, line 1: 5 columns, which no text file aavio reads has"),
            std::string::npos)
      << r.err;
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
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("did you mean 'mapping.eta'"), std::string::npos) << r.err;
  r = RunAavio({"config", "--set", "mapping.rate_hz=nan"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("mapping.rate_hz: expected a finite number, got 'nan'"), std::string::npos)
      << r.err;
  r = RunAavio({"config", "--set", "mapping.eta=-1"});
  EXPECT_EQ(r.code, kExitUsage);  // a number out of range given as an argument
  EXPECT_NE(r.err.find("invalid configuration: mapping.eta = -1 must be >= 0"), std::string::npos)
      << r.err;
  r = RunAavio({"config", "--preset", "kitti"});
  EXPECT_NE(r.err.find("no preset named 'kitti'"), std::string::npos);
  r = RunAavio({"config", "--config", "/nonexistent.yaml"});
  EXPECT_NE(r.err.find("/nonexistent.yaml: no such file"), std::string::npos);
}

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
  EXPECT_NE(r.out.find("[--set edge_sampling.num_points=2400 sets 2400]"), std::string::npos)
      << r.out;
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
  // Nine pose pairs make no score; ten do.
  const std::string nine = (dir / "nine.txt").string(), ten = (dir / "ten.txt").string();
  std::string nine_text, ten_text;
  for (int i = 0; i < 10; ++i) {
    const std::string line =
        StrFormat("%.2f %.3f %.3f 0 0 0 0 1\n", 100.0 + 0.01 * i, 0.02 * i, 0.001 * i * i);
    if (i < 9) nine_text += line;
    ten_text += line;
  }
  testing::WriteFile(nine, nine_text);
  testing::WriteFile(ten, ten_text);
  r = RunAavio({"eval", "--est", nine, "--gt", g});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("only 9 estimated pose(s)"), std::string::npos) << r.err;
  EXPECT_EQ(RunAavio({"eval", "--est", ten, "--gt", g}).code, kExitOk) << ten_text;
  // An estimate whose stamps mostly miss the ground truth's (here: four per interval, a window of
  // 1 ms) is no score either, though it has many pairs.
  std::string dense;
  for (int k = 0; k < 796; ++k)
    dense += StrFormat("%.4f 0 0 0 0 0 0 1\n", 100.0 + 0.0025 * k);
  testing::WriteFile(dir / "dense.txt", dense);
  r = RunAavio({"eval", "--est", (dir / "dense.txt").string(), "--gt", g, "--max-dt", "0.001"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("only 199 of the 796 estimated poses where the ground truth has poses "
                       "found one within 1 ms (25 %, under 50 %)"),
            std::string::npos)
      << r.err;
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
  // The sequence names the truth, and a run says how far its calibration is from it.
  const std::string run = (dir / "run").string();
  r = RunAavio({"run", seq, "--out", run, "--quiet"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("calibration against the true one (ground_truth.calibration): disparity at "
                       "infinity "),
            std::string::npos)
      << r.out;
  std::ifstream summary(std::filesystem::path(run) / "summary.json");
  const nlohmann::json error = nlohmann::json::parse(summary)["calibration_error"];
  // The typical sensor's errors: 0.3 px of principal point per camera, 0.03° of rotation, 0.3 %
  // of baseline, 0.2 % of focal length.
  EXPECT_GT(std::abs(error["disparity_offset_px"].get<double>()), 0.0);
  EXPECT_LT(std::abs(error["disparity_offset_px"].get<double>()), 2.0);
  EXPECT_LE(error["disparity_offset_min_px"].get<double>(),
            error["disparity_offset_max_px"].get<double>());
  EXPECT_NEAR(error["fb_ratio"].get<double>(), 1.0, 0.0031);
  EXPECT_NE(error["fb_ratio"].get<double>(), 1.0);
  // info --against: the same comparison of two calibrations, told and in JSON.
  r = RunAavio({"info", (std::filesystem::path(seq) / "calibration").string(), "--against",
                (std::filesystem::path(seq) / "calibration_true").string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("calibration_true: disparity at infinity " +
                       StrFormat("%+.2f px", error["disparity_offset_px"].get<double>())),
            std::string::npos)
      << r.out;
  r = RunAavio({"info", (std::filesystem::path(seq) / "calibration").string(), "--against",
                (std::filesystem::path(seq) / "calibration_true").string(), "--json"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_DOUBLE_EQ(
      nlohmann::json::parse(r.out)["against"]["difference"]["disparity_offset_px"].get<double>(),
      error["disparity_offset_px"].get<double>());
  r = RunAavio({"info", (std::filesystem::path(seq) / "calibration").string(), "--against",
                (dir / "nowhere").string()});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("--against"), std::string::npos) << r.err;
  r = RunAavio({"info", (std::filesystem::path(seq) / "events" / "left" / "events.h5").string(),
                "--against", (std::filesystem::path(seq) / "calibration_true").string()});
  EXPECT_EQ(r.code, kExitUsage);
  // A converted copy still names the truth.
  r = RunAavio({"convert", seq, "--to", "txt", "--out", (dir / "converted").string()});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  {
    const std::vector<char> bytes =
        testing::ReadBytes((dir / "converted" / "sequence.yaml").string());
    const std::string text(bytes.begin(), bytes.end());
    EXPECT_NE(text.find("calibration_true"), std::string::npos) << text;
  }
  // A true calibration that is not there is an error naming the key and the file.
  {
    const std::vector<char> bytes =
        testing::ReadBytes((std::filesystem::path(seq) / "sequence.yaml").string());
    std::string text(bytes.begin(), bytes.end());
    const std::size_t at = text.find("calibration: calibration_true");
    ASSERT_NE(at, std::string::npos) << text;
    text.replace(at, std::string("calibration: calibration_true").size(),
                 "calibration: no_such_calibration");
    std::ofstream(std::filesystem::path(seq) / "broken.yaml") << text;
  }
  r = RunAavio({"run", (std::filesystem::path(seq) / "broken.yaml").string(), "--out",
                (dir / "broken_run").string(), "--quiet"});
  EXPECT_EQ(r.code, kExitError);
  EXPECT_NE(r.err.find("ground_truth.calibration"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no_such_calibration"), std::string::npos) << r.err;
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