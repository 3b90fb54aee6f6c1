#pragma once
/// What a simulation is made of, before any event is generated: the preset, the stereo rig, the
/// camera's motion as a C2 spline, and the scene laid out around it. Shared by `aavio simulate`
/// and by tests and benchmarks that generate events in memory (docs/simulator.md).

#include <optional>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/sim/motion_spline.hpp"
#include "aavio/sim/presets.hpp"
#include "aavio/sim/recorded_motion.hpp"
#include "aavio/sim/scene.hpp"
#include "aavio/sim/sensor_model.hpp"
#include "aavio/sim/world_effects.hpp"

namespace aavio::sim {

/// A stretch of a simulated sequence where something goes wrong on purpose, to see how the
/// odometry loses and regains tracking. Times in seconds of data from the sequence's start.
struct Disturbance {
  enum class Kind {
    kDark,        ///< no events from either camera (the lights go out, a lens is covered)
    kRightOff,    ///< the right camera sends nothing (unplugged)
    kFastMotion,  ///< the camera moves up to `factor` times faster than the motion it follows
                  ///< (speeding up over the first quarter of the stretch, slowing over the last)
    kStop  ///< the camera slows to a standstill over the first quarter of the stretch, stands
           ///< still for the middle half and starts again over the last quarter (a car at a
           ///< red light)
  };
  Kind kind = Kind::kDark;
  double start_s = 0.0;
  double duration_s = 0.0;
  double factor = 4.0;  ///< kFastMotion only

  bool Covers(double t_s) const { return t_s >= start_s && t_s < start_s + duration_s; }
};

struct SimulationRequest {
  std::string preset = "mini";
  std::string out_dir;
  bool overwrite = false;     ///< replace an earlier sequence in out_dir (else it is an error)
  std::string format = "h5";  ///< h5 | bag | txt
  std::optional<double> duration_s;  ///< default: the preset's (or the whole trajectory)
  double start_s = 0.0;              ///< offset into a recorded trajectory
  std::uint64_t seed = 1;
  /// The motion played this many times as fast (0.05–10): the same path in 1/speed of the time,
  /// for slow and fast versions of a motion. Durations and disturbances are in data time.
  double speed = 1.0;
  /// The camera stands still for this long from the start, then speeds up into its motion over
  /// half as long (a start at rest: nothing but noise in view until it moves). 0: it is moving.
  double rest_at_start_s = 0.0;
  /// The scene's texture contrast times this (0.2-3): fainter or bolder patterns, fewer or more
  /// events, on the same geometry (world effects keep theirs).
  double texture_contrast = 1.0;
  std::string scene;                    ///< a scene by name (SceneKindNamed); empty: the preset's
  std::string motion;                   ///< a built-in motion by name; empty: the preset's
  std::string trajectory;               ///< TUM file: follow a recorded camera path (a twin)
  std::string calibration;              ///< ESVO/DSEC calibration replacing the preset's
  std::optional<double> baseline_m;     ///< the rig's baseline replaced (0.01–2 m)
  std::string body_to_camera = "auto";  ///< identity | driving | auto (driving rule for cars)
  bool preview = false;
  std::string sensor = "typical";          ///< ideal | typical | harsh | a sensor YAML file
  std::vector<std::string> effects;        ///< only these effects of the sensor (empty: all)
  std::vector<Disturbance> disturbances;   ///< darkness, a camera off, too fast a motion, a stop
  std::vector<std::string> world_effects;  ///< flicker, moving_objects (world_effects.hpp)

  /// Errors name the field and its bounds (durations up to a day).
  Status Validate() const;
};

struct SimulationWorld {
  SimulationPreset preset;  ///< its events and imu are the sensor model's
  SensorModel sensor;
  geometry::StereoRig rig;              ///< the true rig: what the events follow
  geometry::StereoRig calibration_rig;  ///< what the sequence's calibration says (with errors)
  CameraPath motion;
  MotionSpline spline;  ///< the rectified left camera in the world
  Scene scene;          ///< with the world effects' lights and moving objects
  WorldEffectsAdded world_effects;
  /// The level scene frame (x right, y along gravity, z forward) in the world.
  geometry::RigidTransform T_world_canonical;

  /// Pose of the raw left (side 0) or raw right (side 1) camera at t_ns.
  geometry::RigidTransform T_world_camera(int side, TimeNs t_ns) const;
};

/// Preset (or calibration), motion (built-in or recorded) and scene of a request.
Expected<SimulationWorld> BuildSimulationWorld(const SimulationRequest& request);

}  // namespace aavio::sim
