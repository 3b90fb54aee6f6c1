#include "aavio/pipeline/odometry_config.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "aavio/io/presets.hpp"
#include "aavio/pipeline/sensor_settings.hpp"

namespace aavio::pipeline {
namespace {

TEST(OdometryConfig, DefaultsAreValidAndThePapers) {
  const OdometryConfig config;
  EXPECT_TRUE(config.Validate().ok()) << config.Validate().message();
  EXPECT_DOUBLE_EQ(config.adaptive_accumulation.check_interval_ms, 2.0);   // δt
  EXPECT_DOUBLE_EQ(config.adaptive_accumulation.contrast_threshold, 0.5);  // β
  EXPECT_DOUBLE_EQ(config.mapping.eta, 0.2);                               // η
  EXPECT_EQ(config.adaptive_accumulation.grid_cols, 8);                    // w = 80 px at 640
  EXPECT_EQ(config.imu.mode, imu::ImuMode::kGyro);
}

TEST(OdometryConfig, EveryKeyIsReachableAndUnique) {
  OdometryConfig config;
  auto index = BuildFieldIndex(config);
  EXPECT_EQ(index.fields.size(), index.order.size());  // no key registered twice
  EXPECT_GT(index.order.size(), 60u);
  EXPECT_TRUE(index.fields.count("mapping.static_stereo.zncc_threshold"));
  EXPECT_TRUE(index.fields.count("imu.gyro_bias_rad_s"));
}

// `aavio config --list` prints every key with a one-line description.
TEST(OdometryConfig, EveryKeyHasAOneLineDescription) {
  OdometryConfig config;
  const auto index = BuildFieldIndex(config);
  EXPECT_LE(index.order.size(), 81u);  // a key earns its place: a user tunes it or a preset sets it
  for (const std::string& key : index.order) {
    const std::string& doc = index.fields.at(key).doc;
    EXPECT_FALSE(doc.empty()) << key;
    EXPECT_EQ(doc.find('\n'), std::string::npos) << key;
    EXPECT_LE(doc.size(), 100u) << key;
  }
}

// The reference overlays — ESVO-like (`aavio run --esvo`) and the paper's method as published
// (`--config paper`) — set every aavio addition — each key whose description marks it "(aavio)"
// — to the reference codes' behaviour, which is the addition's default (off), except for the
// few on by default: so no preset's addition survives in the baselines.
class ReferenceOverlay : public ::testing::TestWithParam<const char*> {};

TEST_P(ReferenceOverlay, TurnsOffEveryAavioAddition) {
  Expected<std::vector<ConfigEntry>> overlay = io::OverlayEntries(GetParam());
  ASSERT_TRUE(overlay.ok()) << overlay.status().message();
  // Its small_sensor section (sample budgets on small sensors, config::ResolveOdometryConfig
  // applies it) holds no addition: left out here.
  std::erase_if(*overlay, [](const ConfigEntry& e) {
    return e.key.starts_with(std::string(kSmallSensorSection) + ".");
  });
  std::set<std::string> set_by_overlay;
  for (const ConfigEntry& e : *overlay)
    set_by_overlay.insert(e.key);
  OdometryConfig defaults;
  const auto default_index = BuildFieldIndex(defaults);
  int additions = 0;
  // Each preset on its kind of sensor (the sensor's settings include aavio additions too).
  const std::vector<std::pair<const char*, SensorFacts>> cases = {
      {"indoor", {240, 180, 157.0, 0.148}}, {"driving", {640, 480, 536.0, 0.6}}};
  for (const auto& [preset, sensor] : cases) {
    SCOPED_TRACE(preset);
    OdometryConfig config;
    Expected<std::vector<ConfigEntry>> entries = io::PresetEntries(preset);
    ASSERT_TRUE(entries.ok());
    OdometryConfig scene;
    ASSERT_TRUE(ApplyConfigEntries(*entries, &scene).ok());
    ASSERT_TRUE(
        ApplyConfigEntries(ToConfigEntries(DeriveSensorSettings(sensor, scene)), &config).ok());
    ASSERT_TRUE(ApplyConfigEntries(*entries, &config).ok());
    ASSERT_TRUE(ApplyConfigEntries(*overlay, &config).ok());
    const auto index = BuildFieldIndex(config);
    additions = 0;
    for (const std::string& key : default_index.order) {
      if (default_index.fields.at(key).doc.find("(aavio)") == std::string::npos) continue;
      ++additions;
      EXPECT_TRUE(set_by_overlay.count(key)) << key << " is an aavio addition the overlay leaves";
      // The additions on by default, with the reference codes' value.
      const std::map<std::string, std::string> on_by_default = {
          {"mapping.snap_to_edge_px", "0.0"},
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

INSTANTIATE_TEST_SUITE_P(OdometryConfig, ReferenceOverlay, ::testing::Values("esvo", "paper"));

TEST(OdometryConfig, ValidationNamesTheFieldAndTheRule) {
  struct Case {
    std::string key, value, expected;
  };
  const std::vector<Case> cases = {
      {"time_surface.decay_ms", "-5", "time_surface.decay_ms = -5 must be in [0.1, 10000]"},
      {"mapping.temporal_stereo.min_parallax_px", "-2",
       "mapping.temporal_stereo.min_parallax_px = -2 must be >= 0"},
      {"adaptive_accumulation.check_interval_ms", "20",
       "adaptive_accumulation.check_interval_ms must not exceed window_ms (10)"},
      {"mapping.inv_depth_max", "0.0001",
       "mapping.inv_depth_max = 1e-04 must exceed inv_depth_min (0.001)"},
      {"mapping.static_stereo.zncc_threshold", "1.5",
       "mapping.static_stereo.zncc_threshold = 1.5 must be in (0, 1]"},
      {"mapping.static_stereo.out_of_view_radius_px", "-1",
       "mapping.static_stereo.out_of_view_radius_px = -1 must be in [0, 50]"},
      {"mapping.temporal_stereo.cross_check_px", "-1",
       "mapping.temporal_stereo.cross_check_px = -1 must be"},
      {"edge_sampling.min_spacing_px", "-1",
       "edge_sampling.min_spacing_px = -1 must be in [0, 16]"},
      {"mapping.temporal_stereo.min_translation_m", "0",
       "mapping.temporal_stereo.min_translation_m = 0 must be > 0"},
      {"mapping.temporal_stereo.max_depth_m", "0.5",
       "mapping.temporal_stereo.max_depth_m = 0.5 must exceed min_depth_m (0.8)"},
      {"mapping.depth_refinement.student_t_nu", "2", "student_t_nu = 2 must be in (2, 1000)"},
      {"mapping.bootstrap.min_points", "0", "mapping.bootstrap.min_points = 0 must be in [1,"},
      {"tracking.batch_size", "5000", "tracking.batch_size must not exceed max_points (2000)"},
      {"imu.gyro_bias_rad_s", "[0, 5.7, 0]", "is it in deg/s?"},
      {"imu.time_offset_s", "4.5", "imu.time_offset_s = 4.5 s; an IMU-camera time offset"},
      {"mapping.rate_hz", "200",
       "mapping.rate_hz = 200 must not exceed time_surface.rate_hz (100)"},
      {"mapping.max_points", "3000", "mapping.max_points = 3000 exceeds edge_sampling.num_points"},
      {"pipeline.num_threads", "-1", "pipeline.num_threads = -1 must be in [0, 1024]"},
  };
  for (const Case& c : cases) {
    OdometryConfig config;
    Expected<ConfigEntry> entry = ParseKeyValueOverride(c.key + "=" + c.value);
    ASSERT_TRUE(entry.ok());
    ASSERT_TRUE(ApplyConfigEntries({*entry}, &config).ok()) << c.key;
    Status s = config.Validate();
    ASSERT_FALSE(s.ok()) << c.key << "=" << c.value;
    EXPECT_NE(s.message().find(c.expected), std::string::npos)
        << "expected: " << c.expected << "\n got: " << s.message();
  }
}

}  // namespace
}  // namespace aavio::pipeline
