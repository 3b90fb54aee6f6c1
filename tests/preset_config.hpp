#pragma once
// A shipped preset as an OdometryConfig, for library tests.

#include <gtest/gtest.h>

#include <string>

#include "aavio/io/presets.hpp"
#include "aavio/pipeline/odometry_config.hpp"

namespace aavio::testing {

inline pipeline::OdometryConfig PresetConfig(const std::string& name) {
  pipeline::OdometryConfig config;
  Expected<std::vector<ConfigEntry>> entries = io::PresetEntries(name);
  EXPECT_TRUE(entries.ok()) << entries.status().message();
  if (entries.ok()) {
    const Status applied = ApplyConfigEntries(*entries, &config);
    EXPECT_TRUE(applied.ok()) << applied.message();
  }
  return config;
}

}  // namespace aavio::testing
