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

/// The indoor preset on the mini twin's rig. 160×120 px constrains translation weakly: the
/// preset's correction gate, for 240×180, is widened to 0.3 m.
inline pipeline::OdometryConfig MiniConfig(const std::optional<geometry::StereoRig>& rig) {
  pipeline::OdometryConfig config = PresetConfig("indoor", rig);
  config.tracking.max_correction_m = 0.3;
  return config;
}

}  // namespace aavio::testing
