#include "aavio/io/config_yaml.hpp"

#include <gtest/gtest.h>

#include "aavio/pipeline/odometry_config.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

TEST(ConfigYaml, FlattensSectionsWithLineOrigins) {
  const std::string text =
      "mapping:\n  eta: 0.1\n  static_stereo:\n    zncc_threshold: 0.3\nimu:\n  gyro_bias_rad_s: "
      "[0.01, 0, "
      "0]\n";
  Expected<std::vector<ConfigEntry>> entries = ParseConfigYaml(text, "my.yaml");
  ASSERT_TRUE(entries.ok()) << entries.status().message();
  ASSERT_EQ(entries->size(), 3u);
  EXPECT_EQ((*entries)[0].key, "mapping.eta");
  EXPECT_EQ((*entries)[0].value.origin, "my.yaml:2");
  EXPECT_EQ((*entries)[1].key, "mapping.static_stereo.zncc_threshold");
  EXPECT_TRUE((*entries)[2].value.is_list);
  pipeline::OdometryConfig config;
  ASSERT_TRUE(ApplyConfigEntries(*entries, &config).ok());
  EXPECT_DOUBLE_EQ(config.mapping.eta, 0.1);
  EXPECT_DOUBLE_EQ(config.mapping.static_stereo.zncc_threshold, 0.3);
  EXPECT_DOUBLE_EQ(config.imu.gyro_bias_rad_s[0], 0.01);
}

TEST(ConfigYaml, UnknownKeysAndBadValuesNameFileAndLine) {
  pipeline::OdometryConfig config;
  auto apply = [&](const std::string& text) {
    Expected<std::vector<ConfigEntry>> entries = ParseConfigYaml(text, "my.yaml");
    if (!entries) return entries.status();
    return ApplyConfigEntries(*entries, &config);
  };
  Status s = apply("mapping:\n  static_stereo:\n    zncc_thresold: 0.2\n");
  EXPECT_NE(s.message().find("unknown configuration key 'mapping.static_stereo.zncc_thresold' "
                             "(my.yaml:3); did you mean 'mapping.static_stereo.zncc_threshold'?"),
            std::string::npos)
      << s.message();
  s = apply("tracking:\n  max_iterations: ten\n");
  EXPECT_NE(s.message().find("tracking.max_iterations: expected an integer, got 'ten' (my.yaml:2)"),
            std::string::npos)
      << s.message();
  s = apply("mapping:\n  fusion:\n    strategy: newest\n");
  EXPECT_NE(s.message().find("expected one of const_frames|const_points"), std::string::npos);
  s = apply("mapping:\n  eta:\n");
  EXPECT_NE(s.message().find("my.yaml:2: mapping.eta has no value"), std::string::npos)
      << s.message();
  s = apply("mapping:\n  eta: [1, 2\n");
  EXPECT_NE(s.message().find("YAML syntax error"), std::string::npos);
  s = apply("imu:\n  gyro_bias_rad_s: [[1], 2, 3]\n");
  EXPECT_NE(s.message().find("must be a flat list"), std::string::npos);
  // Keys that are not names, a file that is a list: errors, not exceptions.
  s = apply("tracking:\n  [max_iterations]: 20\n");
  EXPECT_NE(s.message().find("my.yaml:2: a key must be a name"), std::string::npos) << s.message();
  s = apply("- tracking\n- mapping\n");
  EXPECT_NE(s.message().find("my.yaml:1: expected a mapping of keys at the top level"),
            std::string::npos)
      << s.message();
}

TEST(ConfigYaml, AKeyGivenTwiceIsRefusedWithBothLines) {
  const Expected<std::vector<ConfigEntry>> twice =
      ParseConfigYaml("mapping:\n  rate_hz: 10\n  eta: 0.1\n  rate_hz: 20\n", "c.yaml");
  ASSERT_FALSE(twice.ok());
  EXPECT_EQ(twice.status().message(),
            "c.yaml:4: key 'rate_hz' is given twice (first on line 2); keep one");
}

TEST(ConfigYaml, WrittenConfigReadsBackIdentically) {
  pipeline::OdometryConfig config;
  config.mapping.eta = 0.123456789;
  config.imu.gyro_bias_rad_s = {1e-3, -2e-3, 0.5e-3};
  config.mapping.fusion.strategy = mapping::FusionStrategy::kConstPoints;
  const std::string yaml = FormatConfigYaml(FlattenConfig(config), "test header\nline 2");
  EXPECT_EQ(yaml.rfind("# test header\n# line 2\n", 0), 0u);
  const std::string path = testing::WriteFile(testing::ScratchDir() / "config.yaml", yaml);
  Expected<std::vector<ConfigEntry>> entries = ReadConfigYaml(path);
  ASSERT_TRUE(entries.ok()) << entries.status().message();
  pipeline::OdometryConfig back;
  ASSERT_TRUE(ApplyConfigEntries(*entries, &back).ok());
  EXPECT_EQ(FormatConfigYaml(FlattenConfig(back), ""), FormatConfigYaml(FlattenConfig(config), ""));
  EXPECT_EQ(back.mapping.eta, 0.123456789);
  EXPECT_EQ(entries->size(), FlattenConfig(config).size());
}

TEST(ConfigYaml, WriteTextFileReportsUnwritablePaths) {
  Status s = WriteTextFile("/nonexistent/folder/config.yaml", "x");
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find("/nonexistent/folder/config.yaml"), std::string::npos);
}

}  // namespace
}  // namespace aavio::io
