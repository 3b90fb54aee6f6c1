#pragma once
/// The simulated sensor as a whole: the event cameras' pixel and readout effects
/// (event_generator.hpp), the IMU's noise and biases (imu_synthesis.hpp), and the rig's timing and
/// calibration errors. Named levels — `ideal`, `typical`, `harsh` — or a YAML file describe one;
/// every effect can be switched on alone (docs/simulator.md, "The sensor model").

#include <cstdint>
#include <string>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/common/status.hpp"
#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/sim/event_generator.hpp"
#include "aavio/sim/imu_synthesis.hpp"

namespace aavio::sim {

struct SimulationPreset;

/// Timing and calibration errors of the rig. Calibration errors have the stated size and a
/// direction drawn from the seed: the events follow the true rig, the odometry is handed the
/// perturbed calibration.
struct RigErrorConfig {
  double right_clock_offset_us = 0.0;     ///< right camera's timestamps minus the left's
  double imu_time_offset_ms = 0.0;        ///< IMU timestamps minus the cameras'
  double focal_error = 0.0;               ///< relative error of the focal lengths (both cameras)
  double principal_point_error_px = 0.0;  ///< principal point shift (each camera)
  double baseline_error = 0.0;            ///< relative error of the baseline
  double rotation_error_deg = 0.0;        ///< error of the right camera's rotation

  template <typename V>
  void VisitFields(V&& v) {
    v("right_clock_offset_us", right_clock_offset_us);
    v("imu_time_offset_ms", imu_time_offset_ms);
    v("focal_error", focal_error);
    v("principal_point_error_px", principal_point_error_px);
    v("baseline_error", baseline_error);
    v("rotation_error_deg", rotation_error_deg);
  }
  Status Validate() const;
  bool PerturbsCalibration() const {
    return focal_error != 0.0 || principal_point_error_px != 0.0 || baseline_error != 0.0 ||
           rotation_error_deg != 0.0;
  }
};

struct SensorModel {
  std::string name;  ///< the level or file it came from, and the effects kept ("typical: leak")
  EventCameraConfig events;
  ImuNoiseModel imu;
  RigErrorConfig rig;

  template <typename V>
  void VisitFields(V&& v) {
    v("events", events);
    v("imu", imu);
    v("rig", rig);
  }
  Status Validate() const;
};

/// "ideal", "typical", "harsh".
std::vector<std::string> SensorLevelNames();
/// The effects that can be switched on alone, with what each covers.
struct SensorEffect {
  const char* name;
  const char* description;
};
const std::vector<SensorEffect>& SensorEffects();

/// The sensor of `preset` at `level` — a level name, or a YAML file (sections events / imu / rig,
/// applied on top of `typical`). With `effects` non-empty, only those effects are taken from the
/// level and everything else stays ideal. `ideal` is the preset's own plain model (the figures
/// of earlier releases).
Expected<SensorModel> MakeSensorModel(const SimulationPreset& preset, const std::string& level,
                                      const std::vector<std::string>& effects);

/// The calibration a user would have: `true_rig` with the calibration errors of `errors`
/// (directions and signs drawn from `seed`), rectification and projections kept consistent.
Expected<geometry::StereoRig> PerturbCalibration(const geometry::StereoRig& true_rig,
                                                 const RigErrorConfig& errors, std::uint64_t seed);

}  // namespace aavio::sim
