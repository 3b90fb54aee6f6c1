#include "aavio/sim/sensor_model.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "aavio/sim/presets.hpp"
#include "tests/test_utils.hpp"

namespace aavio::sim {
namespace {

SimulationPreset Rpg() {
  return *GetSimulationPreset("rpg");
}

TEST(SensorModel, IdealIsThePresetsOwnSensor) {
  const Expected<SensorModel> ideal = MakeSensorModel(Rpg(), "ideal", {});
  ASSERT_TRUE(ideal.ok()) << ideal.status().message();
  EXPECT_EQ(FlattenConfig(ideal->events).size(), FlattenConfig(Rpg().events).size());
  for (const ConfigEntry& e : FlattenConfig(ideal->events)) {
    bool found = false;
    for (const ConfigEntry& p : FlattenConfig(Rpg().events)) {
      if (p.key == e.key) {
        EXPECT_EQ(p.value.scalar, e.value.scalar) << e.key;
        found = true;
      }
    }
    EXPECT_TRUE(found) << e.key;
  }
  EXPECT_FALSE(ideal->rig.PerturbsCalibration());
  EXPECT_EQ(ideal->rig.imu_time_offset_ms, 0.0);
}

TEST(SensorModel, LevelsGrowHarsher) {
  const SensorModel typical = *MakeSensorModel(Rpg(), "typical", {});
  const SensorModel harsh = *MakeSensorModel(Rpg(), "harsh", {});
  EXPECT_GT(typical.events.threshold_on, typical.events.threshold_off);
  EXPECT_GT(typical.events.bandwidth_hz, harsh.events.bandwidth_hz);
  EXPECT_GT(harsh.events.leak_rate_hz, typical.events.leak_rate_hz);
  EXPECT_GT(harsh.events.shot_noise_rate_hz, typical.events.shot_noise_rate_hz);
  EXPECT_GT(harsh.events.timestamp_jitter_us, typical.events.timestamp_jitter_us);
  EXPECT_LT(harsh.events.max_rate_mev_s, typical.events.max_rate_mev_s);
  EXPECT_GT(harsh.rig.focal_error, typical.rig.focal_error);
  EXPECT_GT(std::abs(harsh.imu.gyro_bias[0]), std::abs(typical.imu.gyro_bias[0]));
  EXPECT_TRUE(typical.rig.PerturbsCalibration());
  EXPECT_EQ(typical.name, "typical");
}

TEST(SensorModel, OneEffectAloneLeavesTheRestIdeal) {
  const SensorModel ideal = *MakeSensorModel(Rpg(), "ideal", {});
  const SensorModel harsh = *MakeSensorModel(Rpg(), "harsh", {});
  const Expected<SensorModel> leak = MakeSensorModel(Rpg(), "harsh", {"background"});
  ASSERT_TRUE(leak.ok());
  EXPECT_EQ(leak->events.leak_rate_hz, harsh.events.leak_rate_hz);
  EXPECT_EQ(leak->events.noise_rate_hz, harsh.events.noise_rate_hz);
  EXPECT_EQ(leak->events.bandwidth_hz, ideal.events.bandwidth_hz);
  EXPECT_EQ(leak->events.threshold_on, ideal.events.threshold_on);
  EXPECT_EQ(leak->imu.gyro_bias, ideal.imu.gyro_bias);
  EXPECT_FALSE(leak->rig.PerturbsCalibration());
  EXPECT_EQ(leak->name, "harsh: background");

  const Expected<SensorModel> two = MakeSensorModel(Rpg(), "typical", {"calibration", "imu"});
  ASSERT_TRUE(two.ok());
  EXPECT_TRUE(two->rig.PerturbsCalibration());
  EXPECT_EQ(two->rig.imu_time_offset_ms, 0.0);
  EXPECT_NE(two->imu.gyro_bias, ideal.imu.gyro_bias);
  EXPECT_EQ(two->events.leak_rate_hz, 0.0);

  // Every effect named, alone, changes something of the typical sensor.
  for (const SensorEffect& effect : SensorEffects()) {
    const SensorModel alone = *MakeSensorModel(Rpg(), "typical", {effect.name});
    const auto a = FlattenConfig(alone), i = FlattenConfig(ideal);
    bool differs = false;
    for (std::size_t k = 0; k < a.size(); ++k)
      differs |= a[k].value.scalar != i[k].value.scalar || a[k].value.list != i[k].value.list;
    EXPECT_TRUE(differs) << effect.name;
  }
}

TEST(SensorModel, UnknownNamesAreRefusedWithTheChoices) {
  const Expected<SensorModel> level = MakeSensorModel(Rpg(), "realistic", {});
  ASSERT_FALSE(level.ok());
  EXPECT_NE(level.status().message().find("ideal, typical, harsh"), std::string::npos);
  const Expected<SensorModel> effect = MakeSensorModel(Rpg(), "typical", {"lek"});
  ASSERT_FALSE(effect.ok());
  EXPECT_NE(effect.status().message().find("background"), std::string::npos);
}

TEST(SensorModel, FileIsAppliedOnTopOfTypical) {
  const std::filesystem::path dir = aavio::testing::ScratchDir();
  const std::string path = (dir / "my_sensor.yaml").string();
  std::ofstream(path) << "events:\n  leak_rate_hz: 0.7\nrig:\n  imu_time_offset_ms: 2.5\n";
  const Expected<SensorModel> mine = MakeSensorModel(Rpg(), path, {});
  ASSERT_TRUE(mine.ok()) << mine.status().message();
  EXPECT_EQ(mine->events.leak_rate_hz, 0.7);
  EXPECT_EQ(mine->rig.imu_time_offset_ms, 2.5);
  EXPECT_EQ(mine->events.bandwidth_hz, MakeSensorModel(Rpg(), "typical", {})->events.bandwidth_hz);

  std::ofstream(path) << "events:\n  leak_rate: 0.7\n";
  const Expected<SensorModel> typo = MakeSensorModel(Rpg(), path, {});
  ASSERT_FALSE(typo.ok());
  EXPECT_NE(typo.status().message().find(path), std::string::npos);
  EXPECT_NE(typo.status().message().find("leak_rate_hz"), std::string::npos);  // did you mean

  std::ofstream(path) << "events:\n  bandwidth_hz: -5\n";
  const Expected<SensorModel> absurd = MakeSensorModel(Rpg(), path, {});
  ASSERT_FALSE(absurd.ok());
  EXPECT_NE(absurd.status().message().find("events.bandwidth_hz"), std::string::npos);
}

TEST(SensorModel, PerturbedCalibrationHasTheStatedErrors) {
  const geometry::StereoRig truth = *Rpg().rig();
  RigErrorConfig errors;
  errors.focal_error = 0.01;
  errors.principal_point_error_px = 2.0;
  errors.baseline_error = 0.02;
  errors.rotation_error_deg = 0.5;
  std::vector<std::string> warnings;
  const Expected<geometry::StereoRig> perturbed = PerturbCalibration(truth, errors, 3);
  ASSERT_TRUE(perturbed.ok()) << perturbed.status().message();
  const auto& t = truth.left().intrinsics();
  const auto& p = perturbed->left().intrinsics();
  EXPECT_NEAR(std::abs(p.fx / t.fx - 1.0), 0.01, 1e-9);
  EXPECT_NEAR(std::hypot(p.cx - t.cx, p.cy - t.cy), 2.0, 1e-9);
  EXPECT_NEAR(std::abs(perturbed->baseline_m() / truth.baseline_m() - 1.0), 0.02, 1e-6);
  const Eigen::Matrix3d dR = perturbed->T_right_left().R * truth.T_right_left().R.transpose();
  EXPECT_NEAR(Eigen::AngleAxisd(dR).angle() * 180.0 / 3.14159265358979, 0.5, 1e-6);
  // Rectification stays consistent with the claimed extrinsic: R_rect_L = R_rect_R · R_right_left.
  const Eigen::Matrix3d consistency = perturbed->R_rect_right_right() *
                                      perturbed->T_right_left().R *
                                      perturbed->R_rect_left_left().transpose();
  EXPECT_LT(Eigen::AngleAxisd(consistency).angle(),
            Eigen::AngleAxisd(truth.R_rect_right_right() * truth.T_right_left().R *
                              truth.R_rect_left_left().transpose())
                    .angle() +
                1e-6);
  // Another seed, another direction; no errors, the rig itself.
  const auto other = PerturbCalibration(truth, errors, 4);
  EXPECT_NE(other->left().intrinsics().cx, p.cx);
  const auto same = PerturbCalibration(truth, RigErrorConfig{}, 3);
  EXPECT_EQ(same->left().intrinsics().fx, t.fx);
}

}  // namespace
}  // namespace aavio::sim
