#pragma once
/// `aavio run --gt-map` (tracking alone against ground-truth maps); the caller opens the sequence.

#include <string>

#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "cli.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {

struct RunRequest {
  OpenedSequence* sequence = nullptr;
  const geometry::PoseBuffer* gt_poses = nullptr;
  const pipeline::OdometryConfig* config = nullptr;
  TimeNs begin_ns = 0, end_ns = 0;
  std::string out_dir;
};

Status RunTrackingOnGtMap(const RunRequest& request, Context& ctx);

}  // namespace aavio::cli
