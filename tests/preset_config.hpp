#pragma once
// A shipped preset on a rig as an OdometryConfig (the sensor's settings, then the preset, as
// `aavio run` resolves them), for library tests.

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "aavio/config/config_sources.hpp"

namespace aavio::testing {

inline pipeline::OdometryConfig PresetConfig(const std::string& name,
                                             const std::optional<geometry::StereoRig>& rig) {
  EXPECT_TRUE(rig.has_value()) << "no rig: the sequence could not be simulated";
  if (!rig) return {};
  config::ConfigSources sources{.preset = name};
  config::ConfigureForRig(*rig, &sources);
  Expected<pipeline::OdometryConfig> config = config::ResolveOdometryConfig(sources);
  EXPECT_TRUE(config.ok()) << config.status().message();
  return config.ok() ? *config : pipeline::OdometryConfig{};
}

}  // namespace aavio::testing
