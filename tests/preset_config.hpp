#pragma once
// A shipped preset on a rig as an OdometryConfig (the sensor's settings, then the preset, as
// `aavio run` resolves them), for library tests.

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/io/presets.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "aavio/pipeline/sensor_settings.hpp"

namespace aavio::testing {

inline pipeline::OdometryConfig PresetConfig(const std::string& name,
                                             const std::optional<geometry::StereoRig>& rig) {
  Expected<std::vector<ConfigEntry>> preset = io::PresetEntries(name);
  EXPECT_TRUE(preset.ok()) << preset.status().message();
  EXPECT_TRUE(rig.has_value()) << "no rig: the sequence could not be simulated";
  if (!preset.ok() || !rig) return {};
  pipeline::OdometryConfig scene;
  EXPECT_TRUE(ApplyConfigEntries(*preset, &scene).ok());
  const std::vector<pipeline::SensorSetting> derived =
      pipeline::DeriveSensorSettings(pipeline::SensorFacts::Of(*rig), scene);
  pipeline::OdometryConfig config;
  const Status applied = ApplyConfigEntries(pipeline::ToConfigEntries(derived), &config);
  EXPECT_TRUE(applied.ok()) << applied.message();
  EXPECT_TRUE(ApplyConfigEntries(*preset, &config).ok());
  return config;
}

}  // namespace aavio::testing
