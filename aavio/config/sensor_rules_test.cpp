#include "aavio/config/sensor_rules.hpp"

#include <gtest/gtest.h>

#include <map>

#include "aavio/config/presets.hpp"

namespace aavio::config {
namespace {

// The rectified rigs of the shipped calibrations (`aavio info`).
const SensorFacts kRpg{240, 180, 156.925, 0.1480};
const SensorFacts kDsec{640, 480, 536.058, 0.5990};
const SensorFacts kMvsec{346, 260, 199.653, 0.0999};
const SensorFacts kTumVie{1280, 720, 974.825, 0.1185};

using pipeline::OdometryConfig;

OdometryConfig Preset(const std::string& name) {
  OdometryConfig config;
  Expected<std::vector<ConfigEntry>> entries = PresetEntries(name);
  EXPECT_TRUE(entries.ok()) << entries.status().message();
  if (entries) {
    EXPECT_TRUE(ApplyConfigEntries(*entries, &config).ok());
  }
  return config;
}

// What each rule gives on a preset's scene.
std::vector<SensorRuling> Rulings(const SensorFacts& sensor, OdometryConfig config) {
  return ApplySensorRules(sensor, {}, &config);
}

std::map<std::string, std::string> Derive(const SensorFacts& sensor, const std::string& preset) {
  std::map<std::string, std::string> values;
  for (const SensorRuling& s : Rulings(sensor, Preset(preset))) {
    EXPECT_FALSE(s.rule.empty()) << s.key;
    EXPECT_TRUE(s.applied) << s.key;
    values[s.key] = s.value;
  }
  return values;
}

// On the rigs the reference values were chosen for, the rules give them back: the former rpg
// and dsec presets' values.
TEST(SensorSettings, ReproduceTheReferenceValuesOnTheirRigs) {
  const std::map<std::string, std::string> rpg = Derive(kRpg, "indoor");
  const std::map<std::string, std::string> rpg_expected = {
      {"time_surface.rate_hz", "100"},
      {"adaptive_accumulation.grid_cols", "8"},
      {"adaptive_accumulation.grid_rows", "6"},
      {"edge_sampling.grid_cols", "4"},
      {"edge_sampling.grid_rows", "3"},
      {"edge_sampling.num_points", "2000"},
      {"mapping.max_points", "2000"},
      {"edge_sampling.min_spacing_px", "0"},
      {"mapping.static_stereo.smooth_time_surface", "false"},
      {"mapping.depth_refinement.max_inv_depth_stddev", "0.015"},
      {"mapping.depth_refinement.max_relative_stddev", "0.035"}};
  EXPECT_EQ(rpg, rpg_expected);
  const std::map<std::string, std::string> dsec = Derive(kDsec, "driving");
  const std::map<std::string, std::string> dsec_expected = {
      {"time_surface.rate_hz", "100"},
      {"adaptive_accumulation.grid_cols", "8"},
      {"adaptive_accumulation.grid_rows", "6"},
      {"edge_sampling.grid_cols", "8"},
      {"edge_sampling.grid_rows", "6"},
      {"edge_sampling.num_points", "2500"},
      {"mapping.max_points", "2500"},
      {"edge_sampling.min_spacing_px", "2"},
      {"mapping.static_stereo.smooth_time_surface", "true"},
      {"mapping.depth_refinement.max_inv_depth_stddev", "0.015"},  // driving.yaml turns it off
      {"mapping.depth_refinement.max_relative_stddev", "0.1"}};
  EXPECT_EQ(dsec, dsec_expected);
}

TEST(SensorSettings, FollowTheResolutionAndTheDisparityElsewhere) {
  const std::map<std::string, std::string> tum = Derive(kTumVie, "indoor");
  EXPECT_EQ(tum.at("time_surface.rate_hz"), "40");
  EXPECT_EQ(tum.at("adaptive_accumulation.grid_rows"), "5");  // 8 × 720 / 1280 = 4.5
  EXPECT_EQ(tum.at("edge_sampling.grid_cols"), "16");         // 80 px blocks
  EXPECT_EQ(tum.at("edge_sampling.grid_rows"), "9");
  EXPECT_EQ(tum.at("edge_sampling.num_points"), "2500");
  // f·b 115.5 px·m at 1/√(0.2 · 2) m: 73 px of disparity, so 0.51 px is 0.7 %.
  EXPECT_EQ(tum.at("mapping.depth_refinement.max_relative_stddev"), "0.007");
  // DAVIS346: a small sensor, a shorter f·b than rpg's: a looser cull.
  const std::map<std::string, std::string> mvsec = Derive(kMvsec, "indoor");
  EXPECT_EQ(mvsec.at("edge_sampling.num_points"), "2000");
  EXPECT_EQ(mvsec.at("mapping.depth_refinement.max_relative_stddev"), "0.04");
  EXPECT_EQ(mvsec.at("mapping.depth_refinement.max_inv_depth_stddev"), "0.015");
  // A 5 cm DAVIS240C pair (f·b 7.8 px·m): ESVO's 0.015 1/m would ask 0.12 px of disparity.
  const std::map<std::string, std::string> narrow = Derive({240, 180, 156.925, 0.05}, "indoor");
  EXPECT_EQ(narrow.at("mapping.depth_refinement.max_inv_depth_stddev"), "0.0255");  // 0.2 px
  // A wider depth range moves the middle of it, and the cull with it.
  OdometryConfig far = Preset("indoor");
  far.mapping.inv_depth_min = 0.05;
  for (const SensorRuling& s : Rulings(kMvsec, far)) {
    if (s.key == "mapping.depth_refinement.max_relative_stddev") {
      EXPECT_EQ(s.value, "0.081");
    }
  }
}

TEST(SensorSettings, ApplyOnTopOfTheDefaultsAndValidate) {
  for (const SensorFacts& sensor : {kRpg, kDsec, kMvsec, kTumVie, SensorFacts{64, 48, 50, 0.1}}) {
    SCOPED_TRACE(sensor.Describe());
    OdometryConfig config;
    ApplySensorRules(sensor, {}, &config);
    EXPECT_TRUE(config.Validate().ok()) << config.Validate().message();
  }
}

// The rules set typed fields, the value they print is the value set, and a key a source set
// keeps the source's value.
TEST(SensorSettings, SetTheFieldsNoSourceSet) {
  OdometryConfig config;
  config.edge_sampling.num_points = 777;
  const std::vector<SensorRuling> rulings =
      ApplySensorRules(kTumVie, {"edge_sampling.num_points"}, &config);
  EXPECT_EQ(config.edge_sampling.num_points, 777);
  EXPECT_EQ(config.time_surface.rate_hz, 40.0);
  EXPECT_EQ(config.edge_sampling.grid_cols, 16);
  EXPECT_TRUE(config.mapping.static_stereo.smooth_time_surface);
  const auto index = BuildFieldIndex(config);
  for (const SensorRuling& r : rulings) {
    SCOPED_TRACE(r.key);
    EXPECT_EQ(r.applied, r.key != "edge_sampling.num_points");
    if (!r.applied) continue;
    // The printed value reads back as the value set.
    OdometryConfig read_back;
    ASSERT_TRUE(ApplyConfigEntries({{r.key, ConfigValue{.scalar = r.value}}}, &read_back).ok());
    EXPECT_EQ(BuildFieldIndex(read_back).fields.at(r.key).get().scalar,
              index.fields.at(r.key).get().scalar);
  }
}

// A depth range that makes no sense gets no cull from it: the validation names the range.
TEST(SensorSettings, SkipTheCullWithoutADepthRange) {
  OdometryConfig bad = Preset("indoor");
  bad.mapping.inv_depth_min = -1.0;
  for (const SensorRuling& s : Rulings(kRpg, bad))
    EXPECT_NE(s.key, "mapping.depth_refinement.max_relative_stddev") << s.value;
}

TEST(SensorSettings, SuggestAPresetByTheBaseline) {
  EXPECT_EQ(SuggestPreset(kDsec).name, "driving");
  EXPECT_EQ(SuggestPreset(kRpg).name, "indoor");
  EXPECT_EQ(SuggestPreset(kTumVie).name, "indoor");
  EXPECT_NE(SuggestPreset(kTumVie).reason.find("baseline 0.12 m < 0.3 m"), std::string::npos)
      << SuggestPreset(kTumVie).reason;
  // Every suggestion is a shipped preset.
  const std::vector<std::string> names = PresetNames();
  for (const SensorFacts& s : {kDsec, kRpg}) {
    EXPECT_NE(std::find(names.begin(), names.end(), SuggestPreset(s).name), names.end());
  }
}

}  // namespace
}  // namespace aavio::config
