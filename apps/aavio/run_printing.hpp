#pragma once
// The lines `aavio run` ends with: what ran, how fast, how accurate, where the outputs are.

#include <optional>
#include <string>

#include "aavio/io/trajectory_io.hpp"
#include "aavio/recording/run_recorder.hpp"
#include "cli.hpp"
#include "ground_truth_maps.hpp"

namespace aavio::cli {

struct RunPrintout {
  bool mapping_only = false;  ///< --gt-poses
  std::string out_dir;
  io::TrajectoryFormat format = io::TrajectoryFormat::kTum;  ///< --format
  /// --gt-map: the tracking's error against the ground truth, and the IMU mode it ran with.
  std::optional<RelativeError100Ms> tracking_error;
  std::string imu_mode;
};

void PrintRun(const recording::RunRecord& record, const RunPrintout& run, Context& ctx);

}  // namespace aavio::cli
