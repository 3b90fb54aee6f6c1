#include "aavio/config/presets.hpp"

#include <gtest/gtest.h>

#include "aavio/pipeline/odometry_config.hpp"

namespace aavio::config {
namespace {

TEST(Presets, EveryPresetAppliesAndValidates) {
  const std::vector<std::string> names = PresetNames();
  EXPECT_EQ(names, (std::vector<std::string>{"driving", "indoor"}));
  for (const std::string& name : names) {
    Expected<std::vector<ConfigEntry>> entries = PresetEntries(name);
    ASSERT_TRUE(entries.ok()) << entries.status().message();
    pipeline::OdometryConfig config;
    ASSERT_TRUE(ApplyConfigEntries(*entries, &config).ok()) << name;
    EXPECT_TRUE(config.Validate().ok()) << name << ": " << config.Validate().message();
  }
}

TEST(Presets, CarryTheirScenesValues) {
  pipeline::OdometryConfig indoor, driving;
  ASSERT_TRUE(ApplyConfigEntries(*PresetEntries("indoor"), &indoor).ok());
  ASSERT_TRUE(ApplyConfigEntries(*PresetEntries("driving"), &driving).ok());
  EXPECT_DOUBLE_EQ(indoor.mapping.inv_depth_min, 0.2);  // 0.5–5 m indoors
  EXPECT_DOUBLE_EQ(indoor.mapping.inv_depth_max, 2.0);
  EXPECT_EQ(indoor.mapping.fusion.strategy, mapping::FusionStrategy::kConstPoints);  // ESVO rpg
  EXPECT_DOUBLE_EQ(driving.mapping.inv_depth_max, 0.25);                             // from 4 m
  EXPECT_EQ(driving.mapping.fusion.strategy, mapping::FusionStrategy::kConstFrames);
  EXPECT_EQ(PresetEntries("kitti").status().message(),
            "no preset named 'kitti'; presets: driving, indoor");
}

}  // namespace
}  // namespace aavio::config
