#include "aavio/config/config_sources.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "aavio/common/format.hpp"
#include "aavio/config/presets.hpp"
#include "aavio/sim/presets.hpp"
#include "tests/test_utils.hpp"

namespace aavio::config {
namespace {

geometry::StereoRig Rig(const std::string& simulation_preset) {
  Expected<sim::SimulationPreset> preset = sim::GetSimulationPreset(simulation_preset);
  EXPECT_TRUE(preset.ok());
  Expected<geometry::StereoRig> rig = preset->rig();
  EXPECT_TRUE(rig.ok()) << rig.status().message();
  return *rig;
}

TEST(ConfigSources, AProgramConfiguresForItsRigInTwoCalls) {
  // No preset named: the rig's baseline picks one and says why; the sensor's settings apply.
  ConfigSources sources;
  const std::string why = ConfigureForRig(Rig("dsec"), &sources);
  EXPECT_EQ(sources.preset, "driving");
  EXPECT_NE(why.find("baseline"), std::string::npos) << why;
  Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(sources);
  ASSERT_TRUE(config.ok()) << config.status().message();
  EXPECT_EQ(config->adaptive_accumulation.grid_cols, 8);  // derived: 8 blocks across
  EXPECT_EQ(DescribeSources(sources), "the sensor's settings + preset driving");

  // A named preset stays, an override wins over everything.
  ConfigSources named{.preset = "indoor", .overrides = {"mapping.rate_hz=5"}};
  EXPECT_EQ(ConfigureForRig(Rig("rpg"), &named), "");
  Expected<pipeline::OdometryConfig> overridden = ResolveOdometryConfig(named);
  ASSERT_TRUE(overridden.ok()) << overridden.status().message();
  EXPECT_EQ(overridden->mapping.rate_hz, 5.0);
}

// A car's baseline in a room: the indoor preset's depth range holding more of the measured scene
// than the driving preset's makes it indoor; a street's keeps it driving. Each reason says what
// was seen.
TEST(ConfigSources, AWideRigInARoomIsIndoorByTheDepthsMeasured) {
  pipeline::SceneDepth near{{1.5, 2.0, 2.4, 3.0, 4.6}, 0.3};  // all within 0.5-5 m, one past 4 m
  ConfigSources room;
  const std::string why = ConfigureForRig(Rig("dsec"), &room, near);
  EXPECT_EQ(room.preset, "indoor");
  EXPECT_NE(why.find("baseline 0.60 m is a car's, but 100 % of the scene's edges within the "
                     "indoor preset's 0.5-5 m, 20 % within the driving preset's 4-1000 m "
                     "(median 2.4 m of 5 edges 0.3 s into the data)"),
            std::string::npos)
      << why;
  pipeline::SceneDepth far{{3.0, 8.0, 12.0, 20.0, 35.0}, 0.6};
  ConfigSources street;
  EXPECT_NE(ConfigureForRig(Rig("dsec"), &street, far).find("80 % within the driving"),
            std::string::npos);
  EXPECT_EQ(street.preset, "driving");
  // A narrow rig stays indoor whatever it measured (far scenes are no reason for a car's preset,
  // only for a wider depth range: below); a named preset is never second-guessed.
  ConfigSources narrow;
  EXPECT_NE(ConfigureForRig(Rig("rpg"), &narrow, far).find("the scene median 12.0 m"),
            std::string::npos);
  EXPECT_EQ(narrow.preset, "indoor");
  ConfigSources named{.preset = "driving"};
  EXPECT_EQ(ConfigureForRig(Rig("dsec"), &named, near), "");
  EXPECT_EQ(named.preset, "driving");
}

// A narrow rig in a street: the indoor preset stays, its depth range reaches the scene — twice
// its 90th-percentile depth, at most where the disparity is half a pixel; --set still wins. In
// a room nothing changes.
TEST(ConfigSources, ANarrowRigSeeingAStreetReachesItsDepths) {
  const geometry::StereoRig rpg = Rig("rpg");
  const double fb = rpg.focal_px() * rpg.baseline_m();
  std::vector<double> street_m;
  for (int i = 0; i < 100; ++i)
    street_m.push_back(4.0 + 0.1 * i);  // 4-13.9 m: 11 % within 0.5-5 m, 90th percentile 13 m
  ConfigSources street;
  const std::string why = ConfigureForRig(rpg, &street, pipeline::SceneDepth{street_m, 0.3});
  EXPECT_EQ(street.preset, "indoor");
  const double far_m = std::ceil(std::min(2.0 * 13.0, fb / 0.5));
  EXPECT_NE(
      why.find(StrFormat("11 %% of it within the preset's 0.5-5 m: depth range 0.5-%g m", far_m)),
      std::string::npos)
      << why;
  Expected<ResolvedConfig> resolved = Resolve(street);
  ASSERT_TRUE(resolved.ok()) << resolved.status().message();
  EXPECT_NEAR(resolved->config.mapping.inv_depth_min, 1.0 / far_m, 1e-6);
  EXPECT_NEAR(resolved->config.mapping.temporal_stereo.max_depth_m, far_m, 1e-6);
  EXPECT_NE(resolved->origin["mapping.inv_depth_min"].find("the measured scene"),
            std::string::npos);
  EXPECT_EQ(DescribeSources(street),
            "the sensor's settings + preset indoor + the measured scene's depth range");

  // Far beyond what the rig resolves: the range stops at half a pixel of disparity.
  ConfigSources very_far;
  ConfigureForRig(rpg, &very_far, pipeline::SceneDepth{{20.0, 40.0, 80.0, 150.0, 300.0}, 0.3});
  Expected<pipeline::OdometryConfig> capped = ResolveOdometryConfig(very_far);
  ASSERT_TRUE(capped.ok()) << capped.status().message();
  EXPECT_NEAR(capped->mapping.inv_depth_min, 1.0 / std::ceil(fb / 0.5), 1e-6);

  ConfigSources set{.overrides = {"mapping.inv_depth_min=0.1"}};
  ConfigureForRig(rpg, &set, pipeline::SceneDepth{street_m, 0.3});
  Expected<pipeline::OdometryConfig> overridden = ResolveOdometryConfig(set);
  ASSERT_TRUE(overridden.ok()) << overridden.status().message();
  EXPECT_EQ(overridden->mapping.inv_depth_min, 0.1);

  ConfigSources room;
  ConfigureForRig(rpg, &room, pipeline::SceneDepth{{1.0, 1.5, 2.0, 3.0, 8.0}, 0.3});
  EXPECT_TRUE(room.scene.empty());
}

// The reference overlays take their code's budget for the rig. ESVO: 1 000 newest events on rpg's
// DAVIS240C, 10 000 on DSEC's rig; the paper's (ICRA code): 5 000 AA samples on rpg of which
// mapping takes 1 000, the sensor's 2 500 on DSEC. Whether named by --esvo or --config, and --set
// still wins.
TEST(ConfigSources, ReferenceOverlaysTakeTheirBudgetForTheSensor) {
  using Budget = std::pair<int, int>;  // sampled, mapped
  auto budget = [](const std::string& rig, ConfigSources sources) {
    ConfigureForRig(Rig(rig), &sources);
    Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(sources);
    EXPECT_TRUE(config.ok()) << config.status().message();
    return Budget{config->edge_sampling.num_points, config->mapping.max_points};
  };
  EXPECT_EQ(budget("rpg", {.overlays = {"esvo"}}), Budget(1000, 1000));
  EXPECT_EQ(budget("rpg", {.files = {"esvo"}}), Budget(1000, 1000));
  EXPECT_EQ(budget("dsec", {.overlays = {"esvo"}}), Budget(10000, 10000));
  EXPECT_EQ(budget("rpg", {}), Budget(2000, 2000));  // AA's budget without an overlay
  EXPECT_EQ(budget("rpg", {.overlays = {"paper"}}), Budget(5000, 1000));
  EXPECT_EQ(budget("dsec", {.files = {"paper"}}), Budget(2500, 2500));
  EXPECT_EQ(
      budget("rpg", {.overlays = {"esvo"},
                     .overrides = {"edge_sampling.num_points=3000", "mapping.max_points=3000"}}),
      Budget(3000, 3000));
}

// A file's small_sensor section applies on a sensor under 0.1 Mpx only, after the file's other
// keys (the reference overlays' budgets are such sections); without a rig, never.
TEST(ConfigSources, AFilesSmallSensorSectionAppliesOnSmallSensorsOnly) {
  const std::string file = (testing::ScratchDir() / "budget.yaml").string();
  testing::WriteFile(file,
                     "tracking:\n  max_iterations: 12\nsmall_sensor:\n  tracking:\n"
                     "    max_iterations: 17\n");
  auto iterations = [&](const std::optional<std::string>& rig) {
    ConfigSources sources{.preset = "indoor", .files = {file}};
    if (rig) ConfigureForRig(Rig(*rig), &sources);
    Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(sources);
    EXPECT_TRUE(config.ok()) << config.status().message();
    return config.ok() ? config->tracking.max_iterations : -1;
  };
  EXPECT_EQ(iterations("rpg"), 17);   // 240 x 180
  EXPECT_EQ(iterations("dsec"), 12);  // 640 x 480
  EXPECT_EQ(iterations(std::nullopt), 12);
}

// `--config esvo` names the shipped overlay unless a configuration file of that name is in the
// working folder; a folder of that name (a run's output, say) does not hide it.
TEST(ConfigSources, AnOverlayNameIsAFileOnlyIfSuchAFileIsThere) {
  struct WorkingFolder {  // restores the working folder whatever the test does
    std::filesystem::path before = std::filesystem::current_path();
    ~WorkingFolder() { std::filesystem::current_path(before); }
  } restore;
  const std::filesystem::path dir = testing::ScratchDir();
  std::filesystem::current_path(dir);
  auto iterations = [](ConfigSources sources) {
    ConfigureForRig(Rig("rpg"), &sources);
    Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(sources);
    EXPECT_TRUE(config.ok()) << config.status().message();
    return config.ok() ? config->tracking.max_iterations : -1;
  };
  std::filesystem::create_directories(dir / "esvo" / "run");
  EXPECT_EQ(iterations({.files = {"esvo"}}), 10);  // the overlay's
  std::filesystem::create_directories(dir / "paper");
  EXPECT_EQ(iterations({.files = {"paper"}}), 10);
  testing::WriteFile(dir / "cfg" / "esvo", "tracking:\n  max_iterations: 7\n");
  std::filesystem::current_path(dir / "cfg");
  EXPECT_EQ(iterations({.files = {"esvo"}}), 7);  // the file here
}

TEST(ConfigSources, BadSourcesAreErrorsThatSayWhatToDo) {
  ConfigSources old_name{.preset = "rpg"};
  Expected<pipeline::OdometryConfig> a = ResolveOdometryConfig(old_name);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("indoor"), std::string::npos) << a.status().message();
  ConfigSources absurd{.overrides = {"mapping.rate_hz=-3"}};
  Expected<pipeline::OdometryConfig> b = ResolveOdometryConfig(absurd);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("rate_hz"), std::string::npos) << b.status().message();
  ConfigSources missing{.files = {"/nonexistent/my.yaml"}};
  Expected<pipeline::OdometryConfig> c = ResolveOdometryConfig(missing);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("/nonexistent/my.yaml"), std::string::npos)
      << c.status().message();
}

// The reference overlays — ESVO-like (`aavio run --esvo`) and the paper's method as published
// (`--config paper`) — set every aavio addition — each key whose description marks it "(aavio)"
// — to the reference codes' behaviour, which is the addition's default (off), except for the
// few on by default: so no preset's addition survives in the baselines.
// Every value says where it came from: a source's file and line or --set, a sensor rule, or the
// default (no origin); a rule a source overrode is listed as not applied.
TEST(ConfigSources, SayWhereEachValueCameFrom) {
  ConfigSources sources{.preset = "indoor", .overrides = {"edge_sampling.num_points=2400"}};
  ConfigureForRig(Rig("rpg"), &sources);
  Expected<ResolvedConfig> resolved = Resolve(sources);
  ASSERT_TRUE(resolved.ok()) << resolved.status().message();
  EXPECT_EQ(resolved->config.edge_sampling.num_points, 2400);
  EXPECT_EQ(resolved->origin.at("edge_sampling.num_points"), "--set edge_sampling.num_points=2400");
  EXPECT_EQ(resolved->origin.at("mapping.inv_depth_min"), "preset indoor:11");
  EXPECT_NE(resolved->origin.at("edge_sampling.grid_cols").find("the sensor's rule (~80 px"),
            std::string::npos);
  EXPECT_FALSE(resolved->origin.contains("mapping.eta"));
  int overridden = 0;
  for (const SensorRuling& r : resolved->sensor_rulings) {
    EXPECT_EQ(r.applied, r.key != "edge_sampling.num_points") << r.key;
    overridden += r.applied ? 0 : 1;
  }
  EXPECT_EQ(overridden, 1);
}

class ReferenceOverlay : public ::testing::TestWithParam<const char*> {};

TEST_P(ReferenceOverlay, TurnsOffEveryAavioAddition) {
  Expected<std::vector<ConfigEntry>> overlay = OverlayEntries(GetParam());
  ASSERT_TRUE(overlay.ok()) << overlay.status().message();
  // Its small_sensor section (sample budgets on small sensors) holds no addition: left out here.
  std::erase_if(*overlay, [](const ConfigEntry& e) {
    return e.key.starts_with(std::string(kSmallSensorSection) + ".");
  });
  std::set<std::string> set_by_overlay;
  for (const ConfigEntry& e : *overlay)
    set_by_overlay.insert(e.key);
  pipeline::OdometryConfig defaults;
  const auto default_index = BuildFieldIndex(defaults);
  int additions = 0;
  // Each preset on its kind of sensor (the sensor's settings include aavio additions too).
  const std::vector<std::pair<const char*, SensorFacts>> cases = {
      {"indoor", {240, 180, 157.0, 0.148}}, {"driving", {640, 480, 536.0, 0.6}}};
  for (const auto& [preset, sensor] : cases) {
    SCOPED_TRACE(preset);
    const ConfigSources sources{.preset = preset, .overlays = {GetParam()}, .sensor = sensor};
    Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(sources);
    ASSERT_TRUE(config.ok()) << config.status().message();
    const auto index = BuildFieldIndex(*config);
    additions = 0;
    for (const std::string& key : default_index.order) {
      if (default_index.fields.at(key).doc.find("(aavio)") == std::string::npos) continue;
      ++additions;
      EXPECT_TRUE(set_by_overlay.count(key)) << key << " is an aavio addition the overlay leaves";
      // The additions on by default, with the reference codes' value.
      const std::map<std::string, std::string> on_by_default = {
          {"mapping.snap_to_edge_px", "0.0"},
          {"mapping.predicted_search", "false"},
          {"mapping.bootstrap.min_coverage", "0.0"},
          {"mapping.fusion.full_at_max_frames", "false"},
          {"time_surface.adaptive_decay", "false"}};
      const auto on = on_by_default.find(key);
      const std::string expected =
          on != on_by_default.end() ? on->second : default_index.fields.at(key).get().scalar;
      EXPECT_EQ(index.fields.at(key).get().scalar, expected) << key;
    }
  }
  EXPECT_GE(additions, 15);
}

INSTANTIATE_TEST_SUITE_P(ConfigSources, ReferenceOverlay, ::testing::Values("esvo", "paper"));

}  // namespace
}  // namespace aavio::config
