#pragma once
/// The simulator's presets (issue 4): a real sensor's calibration figures, a scene, a built-in
/// motion of the same character, and event/IMU settings.
///   rpg    DAVIS240C stereo pair (Zhou et al., ECCV 2018), room, hand-held 6-DoF
///   dsec   the 640×480 event pair of DSEC zurich_city_04_a, street canyon, urban driving
///   mvsec  the DAVIS346 pair of MVSEC (upenn calibration, equidistant), hall, drone flight
///   tum_vie  the 1280×720 Prophesee pair of TUM-VIE (mocap-desk calibration), office, hand-held
///   vector   the 640×480 Prophesee pair of VECtor, lab, hand-held
///   planes an ideal rectified 240×180 pinhole pair (f 200 px, baseline 0.15 m), a sparse scene
///          of a few textured planes, a smooth sinusoidal 6-DoF motion, 8 s
///   mini   the rpg pair at 2/3 resolution (160×120), room, hand-held, 3 s: tests and the demo

#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/sim/event_generator.hpp"
#include "aavio/sim/imu_synthesis.hpp"
#include "aavio/sim/scene_builder.hpp"

namespace aavio::sim {

enum class MotionKind { kHandHeld, kDriving, kDrone, kSinusoid };
/// The sensor family, for the realistic sensor levels (sensor_model.hpp): their refractory
/// period, noise and readout differ.
/// The sensor family, for what the sensor model's levels take from it (refractory period,
/// background activity, readout rate).
enum class CameraKind { kDavis, kProphesee, kDvxplorer };

struct SimulationPreset {
  std::string name;
  std::string description;
  SceneKind scene = SceneKind::kRoom;
  MotionKind motion = MotionKind::kHandHeld;
  CameraKind camera = CameraKind::kDavis;
  double duration_s = 10.0;
  double camera_height_m = 1.4;  ///< above the road (street scenes)
  EventCameraConfig events;
  ImuNoiseModel imu;
  double depth_rate_hz = 20.0;  ///< ground-truth depth/disparity maps
  double pose_rate_hz = 200.0;  ///< ground-truth poses
  /// Builds the preset's stereo rig (its calibration figures are stated in presets.cpp).
  Expected<geometry::StereoRig> (*rig)() = nullptr;
};

/// A scene or motion by name, for mixing a preset's sensor with another preset's scene or motion:
/// room, office, lab, hall, street, planes; hand_held, driving, drone, sinusoid. InvalidArgument
/// listing the names otherwise.
Expected<SceneKind> SceneKindNamed(const std::string& name);
Expected<MotionKind> MotionKindNamed(const std::string& name);

std::vector<std::string> SimulationPresetNames();
/// NotFound listing the presets for an unknown name.
Expected<SimulationPreset> GetSimulationPreset(const std::string& name);

}  // namespace aavio::sim
