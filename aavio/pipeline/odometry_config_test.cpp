#include "aavio/pipeline/odometry_config.hpp"

#include <gtest/gtest.h>

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
  EXPECT_LE(index.order.size(), 83u);  // a key earns its place: a user tunes it or a preset sets it
  for (const std::string& key : index.order) {
    const std::string& doc = index.fields.at(key).doc;
    EXPECT_FALSE(doc.empty()) << key;
    EXPECT_EQ(doc.find('\n'), std::string::npos) << key;
    EXPECT_LE(doc.size(), 100u) << key;
  }
}

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
