#include "aavio/sim/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "aavio/geometry/random_draws.hpp"
#include "aavio/geometry/rotation.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/sim/presets.hpp"

namespace aavio::sim {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

/// The level's values, on top of the preset's own (ideal) sensor. Sources: docs/simulator.md,
/// "The sensor model"; the figures measured on real recordings with `aavio info --stats` are
/// in its table "Real and simulated sensors".
SensorModel Typical(const SensorModel& ideal, CameraKind camera) {
  SensorModel m = ideal;
  EventCameraConfig& e = m.events;
  const bool davis = camera == CameraKind::kDavis;
  // iniVation DVXplorer: a DAVIS's background activity (a quiet one: 0.43 ev/px/s), a
  // Prophesee's short refractory period (0.19 ms: first percentile of its same-pixel intervals).
  const bool dvxplorer = camera == CameraKind::kDvxplorer;
  const bool davis_noise = davis || dvxplorer;
  // Contrast thresholds: ON above OFF (real DAVIS240C recordings fire 0.43–0.45 ON), mismatch
  // σ 0.035 log (DVS/DAVIS characterisations: 2–4 % contrast).
  const double mean = (e.threshold_on + e.threshold_off) / 2.0;
  e.threshold_on = mean * 1.1;
  e.threshold_off = mean / 1.1;
  e.threshold_sigma = 0.035;
  e.bandwidth_hz = 1000.0;  // cutoff at full illumination; a grey 0.3 sees 300 Hz
  // Real DAVIS240C: no pixel fires twice within ~1.7 ms (1st percentile of same-pixel
  // intervals); Prophesee Gen3: 27 µs.
  e.refractory_us = davis ? 1500.0 : dvxplorer ? 190.0 : 25.0;
  e.noise_rate_hz = 0.0;  // background activity comes from leak and shot noise instead
  e.leak_rate_hz = davis_noise ? 0.1 : 0.05;
  e.leak_rate_spread = 0.3;
  e.shot_noise_rate_hz = davis_noise ? 0.5 : 0.2;
  e.hot_pixel_fraction = davis_noise ? 1e-4 : 2e-5;
  e.hot_pixel_rate_hz = davis_noise ? 50.0 : 200.0;
  e.timestamp_jitter_us = 20.0;
  // Datasheets: DAVIS240C/346, DVXplorer (165 Mev/s), Prophesee VGA.
  e.max_rate_mev_s = davis ? 12.0 : dvxplorer ? 165.0 : 50.0;
  // IMU: the MPU-6150 datasheet's white noise, a bias left after a factory calibration.
  const ImuNoiseModel datasheet = ImuNoiseModel::Datasheet();
  m.imu.gyro_noise_density = datasheet.gyro_noise_density;
  m.imu.accel_noise_density = datasheet.accel_noise_density;
  m.imu.gyro_bias = {0.005, -0.004, 0.006};  // ≈ 0.3 °/s
  m.imu.accel_bias = {0.05, -0.08, 0.06};
  // A careful calibration and a hardware-synchronised pair.
  m.rig.right_clock_offset_us = 50.0;
  m.rig.imu_time_offset_ms = 0.5;
  m.rig.focal_error = 0.002;
  m.rig.principal_point_error_px = 0.3;
  m.rig.baseline_error = 0.003;
  m.rig.rotation_error_deg = 0.03;
  return m;
}

SensorModel Harsh(const SensorModel& ideal, CameraKind camera) {
  SensorModel m = Typical(ideal, camera);
  EventCameraConfig& e = m.events;
  const double mean = (e.threshold_on + e.threshold_off) / 2.0;
  e.threshold_on = mean * 1.25;
  e.threshold_off = mean / 1.25;
  e.threshold_sigma = 0.05;
  e.bandwidth_hz = 200.0;  // dim light
  e.refractory_us *= 2.0;
  e.leak_rate_hz = 0.3;
  e.leak_rate_spread = 0.5;
  e.shot_noise_rate_hz = 3.0;
  e.hot_pixel_fraction = 1e-3;
  e.hot_pixel_rate_hz = 200.0;
  e.timestamp_jitter_us = 100.0;
  e.max_rate_mev_s /= 4.0;          // a shared USB link
  m.imu.gyro_noise_density *= 3.0;  // vibration
  m.imu.accel_noise_density *= 3.0;
  m.imu.gyro_bias = {0.02, -0.015, 0.025};  // ≈ 1.2 °/s, an uncalibrated MEMS gyroscope
  m.imu.accel_bias = {0.2, -0.25, 0.15};
  m.rig.right_clock_offset_us = 1000.0;  // unsynchronised cameras, host timestamps
  m.rig.imu_time_offset_ms = 3.0;
  m.rig.focal_error = 0.01;
  m.rig.principal_point_error_px = 1.5;
  m.rig.baseline_error = 0.01;
  m.rig.rotation_error_deg = 0.15;
  return m;
}

struct EffectCopy {
  SensorEffect effect;
  std::function<void(const SensorModel& from, SensorModel* to)> copy;
};

const std::vector<EffectCopy>& EffectCopies() {
  static const std::vector<EffectCopy> copies = {
      {{"thresholds", "ON/OFF asymmetry and per-pixel mismatch of the contrast thresholds"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.threshold_on = f.events.threshold_on;
         t->events.threshold_off = f.events.threshold_off;
         t->events.threshold_sigma = f.events.threshold_sigma;
       }},
      {{"bandwidth", "photoreceptor low-pass, slower in the dark"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.bandwidth_hz = f.events.bandwidth_hz;
       }},
      {{"refractory", "refractory period"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.refractory_us = f.events.refractory_us;
       }},
      {{"background",
        "leak events with a per-pixel rate spread (replace uniform background activity)"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.noise_rate_hz = f.events.noise_rate_hz;
         t->events.leak_rate_hz = f.events.leak_rate_hz;
         t->events.leak_rate_spread = f.events.leak_rate_spread;
       }},
      {{"shot_noise", "shot noise, more frequent in dark pixels"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.shot_noise_rate_hz = f.events.shot_noise_rate_hz;
       }},
      {{"hot_pixels", "pixels that fire on their own"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.hot_pixel_fraction = f.events.hot_pixel_fraction;
         t->events.hot_pixel_rate_hz = f.events.hot_pixel_rate_hz;
       }},
      {{"jitter", "timestamp jitter"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.timestamp_jitter_us = f.events.timestamp_jitter_us;
       }},
      {{"readout", "maximum event rate: events delayed, then dropped, when the readout saturates"},
       [](const SensorModel& f, SensorModel* t) {
         t->events.max_rate_mev_s = f.events.max_rate_mev_s;
       }},
      {{"imu", "IMU white noise and biases"},
       [](const SensorModel& f, SensorModel* t) { t->imu = f.imu; }},
      {{"clock_offset", "left-right camera clock offset"},
       [](const SensorModel& f, SensorModel* t) {
         t->rig.right_clock_offset_us = f.rig.right_clock_offset_us;
       }},
      {{"imu_time_offset", "IMU-camera time offset"},
       [](const SensorModel& f, SensorModel* t) {
         t->rig.imu_time_offset_ms = f.rig.imu_time_offset_ms;
       }},
      {{"calibration",
        "focal length, principal point, baseline and rotation errors of the calibration"},
       [](const SensorModel& f, SensorModel* t) {
         t->rig.focal_error = f.rig.focal_error;
         t->rig.principal_point_error_px = f.rig.principal_point_error_px;
         t->rig.baseline_error = f.rig.baseline_error;
         t->rig.rotation_error_deg = f.rig.rotation_error_deg;
       }},
  };
  return copies;
}

Expected<SensorModel> FromFile(const SensorModel& ideal, CameraKind camera,
                               const std::string& path) {
  Expected<std::vector<ConfigEntry>> entries = io::ReadConfigYaml(path);
  if (!entries) return entries.status();
  SensorModel m = Typical(ideal, camera);
  Status applied = ApplyConfigEntries(*entries, &m);
  if (!applied.ok()) {
    return InvalidArgument(path + ": " + applied.message() +
                           " (a sensor file has the sections events, imu and rig; `aavio simulate "
                           "--sensor typical --print-sensor` prints every key)");
  }
  return m;
}

}  // namespace

Status RigErrorConfig::Validate() const {
  FieldChecker check;
  check.InRange("right_clock_offset_us", right_clock_offset_us, -1e6, 1e6)
      .InRange("imu_time_offset_ms", imu_time_offset_ms, -1000.0, 1000.0)
      .InRange("focal_error", focal_error, 0.0, 0.2)
      .InRange("principal_point_error_px", principal_point_error_px, 0.0, 50.0)
      .InRange("baseline_error", baseline_error, 0.0, 0.5)
      .InRange("rotation_error_deg", rotation_error_deg, 0.0, 10.0);
  return check.status();
}

Status SensorModel::Validate() const {
  FieldChecker check;
  check.Nested("events", events).Nested("imu", imu).Nested("rig", rig);
  return check.status();
}

std::vector<std::string> SensorLevelNames() {
  return {"ideal", "typical", "harsh"};
}

const std::vector<SensorEffect>& SensorEffects() {
  static const std::vector<SensorEffect> effects = [] {
    std::vector<SensorEffect> list;
    for (const EffectCopy& c : EffectCopies())
      list.push_back(c.effect);
    return list;
  }();
  return effects;
}

Expected<SensorModel> MakeSensorModel(const SimulationPreset& preset, const std::string& level,
                                      const std::vector<std::string>& effects) {
  SensorModel ideal;
  ideal.events = preset.events;
  ideal.imu = preset.imu;
  SensorModel full;
  if (level == "ideal") {
    full = ideal;
  } else if (level == "typical") {
    full = Typical(ideal, preset.camera);
  } else if (level == "harsh") {
    full = Harsh(ideal, preset.camera);
  } else if (level.find('.') != std::string::npos || level.find('/') != std::string::npos) {
    Expected<SensorModel> file = FromFile(ideal, preset.camera, level);
    if (!file) return file.status();
    full = *file;
  } else {
    return InvalidArgument("--sensor '" + level +
                           "': use ideal, typical, harsh or a sensor YAML file");
  }
  SensorModel model = full;
  model.name = level;
  if (!effects.empty()) {
    model = ideal;
    model.name = level + ":";
    for (const std::string& name : effects) {
      auto it = std::find_if(EffectCopies().begin(), EffectCopies().end(),
                             [&](const EffectCopy& c) { return name == c.effect.name; });
      if (it == EffectCopies().end()) {
        std::string known;
        for (const SensorEffect& e : SensorEffects())
          known += (known.empty() ? "" : ", ") + std::string(e.name);
        return InvalidArgument("--effects: no sensor effect '" + name + "'; effects: " + known);
      }
      it->copy(full, &model);
      model.name += (model.name.back() == ':' ? " " : ", ") + name;
    }
  }
  if (Status valid = model.Validate(); !valid.ok()) {
    return InvalidArgument("sensor '" + level + "': " + valid.message());
  }
  return model;
}

Expected<geometry::StereoRig> PerturbCalibration(const geometry::StereoRig& true_rig,
                                                 const RigErrorConfig& errors, std::uint64_t seed) {
  if (!errors.PerturbsCalibration()) return true_rig;
  std::mt19937_64 rng(seed * 2 + 17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto sign = [&] { return unit(rng) < 0.5 ? -1.0 : 1.0; };
  auto perturb = [&](geometry::CameraIntrinsics in) {
    const double focal = 1.0 + sign() * errors.focal_error;
    in.fx *= focal;
    in.fy *= focal;
    const double angle = 2.0 * std::numbers::pi * unit(rng);
    in.cx += errors.principal_point_error_px * std::cos(angle);
    in.cy += errors.principal_point_error_px * std::sin(angle);
    return geometry::CameraModel::Create(in);
  };
  Expected<geometry::CameraModel> left = perturb(true_rig.left().intrinsics());
  if (!left) return left.status();
  Expected<geometry::CameraModel> right = perturb(true_rig.right().intrinsics());
  if (!right) return right.status();

  // The right camera believed turned by δR: T_right_left' = δR·T_right_left, and the
  // rectification computed from it, R_rect_right' = R_rect_right·δRᵀ.
  const Eigen::Vector3d axis =
      (geometry::DrawZyx(unit, rng) - Eigen::Vector3d::Constant(0.5)).normalized();
  const Eigen::Matrix3d dR = geometry::ExpSO3(axis * errors.rotation_error_deg * kDegToRad);
  const double baseline = 1.0 + sign() * errors.baseline_error;
  geometry::RigidTransform T_right_left = true_rig.T_right_left();
  T_right_left.R = dR * T_right_left.R;
  T_right_left.t = dR * T_right_left.t * baseline;
  geometry::ProjectionMatrix P_right = true_rig.P_right();
  P_right(0, 3) *= baseline;
  return geometry::StereoRig::Create(
      {*left, *right, true_rig.R_rect_left_left(), true_rig.R_rect_right_right() * dR.transpose(),
       true_rig.P_left(), P_right, T_right_left, true_rig.T_imu_left()});
}

}  // namespace aavio::sim
