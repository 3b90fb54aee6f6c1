#pragma once
/// `aavio simulate`: a stereo event camera + IMU sequence with exact ground truth, written as a
/// sequence folder that `aavio info` and the readers understand (docs/simulator.md):
///   sequence.yaml, calibration/{left,right}.yaml (ESVO style, with T_b_c),
///   events/{left,right}/events.h5 (or one events.bag, or events.txt), imu.txt,
///   calibration_true/ when the sensor model gives the calibration errors,
///   groundtruth.txt (TUM, the rectified left camera in the world of its first pose),
///   depth/ (rectified-left disparity ×256 as 16-bit PNG, metric depth as 32-bit TIFF and edge
///   labels as PNG — 0 none, 128 edge, 255 near-horizontal edge (sim/edge_truth.hpp) — with
///   timestamps.txt), scene.txt (the quads), and preview/ PNGs on request.

#include <functional>
#include <optional>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/sim/world.hpp"

namespace aavio::sim {

struct SimulationReport {
  double duration_s = 0.0;
  double wall_s = 0.0;
  std::int64_t events_left = 0, events_right = 0;
  std::int64_t noise_events = 0;    ///< background activity, leak, shot noise, hot pixels (both)
  std::int64_t dropped_events = 0;  ///< lost in a saturated readout, both cameras
  std::string sensor;               ///< the sensor level (and effects) simulated
  std::int64_t render_steps = 0;
  std::int64_t imu_samples = 0;
  std::int64_t depth_maps = 0;
  double mean_rate_ev_s = 0.0;        ///< per camera
  double pixel_rate_median_hz = 0.0;  ///< events per pixel per second, left camera
  double pixel_rate_p99_hz = 0.0;
  std::string body_to_camera;  ///< the rotation that was used, in words
  std::string path_smoothing;  ///< the recorded path's measurement noise removed, in words
  std::string world_effects;   ///< what the world effects added, in words
  std::string sequence_yaml;
};

/// Runs the simulation; `progress` (if set) is called with the fraction done.
Expected<SimulationReport> Simulate(const SimulationRequest& request,
                                    const std::function<void(double)>& progress = {});

}  // namespace aavio::sim
