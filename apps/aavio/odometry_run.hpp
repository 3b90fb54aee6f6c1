#pragma once
/// `aavio run SEQUENCE --out DIR`: the full odometry on a sequence, with the outputs of
/// design.md §4 — stamped_traj_estimate.txt (TUM), config.yaml, summary.json, timings.csv,
/// map.ply and inverse-depth images — and, when the sequence has ground truth, its accuracy.

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "aavio/pipeline/odometry_config.hpp"
#include "cli.hpp"
#include "run_evaluation.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {

struct OdometryRunRequest {
  OpenedSequence* sequence = nullptr;
  const pipeline::OdometryConfig* config = nullptr;
  std::string config_origin;  ///< for config.yaml's header
  std::string mode = "full";  ///< "full" or "esvo", recorded in summary.json
  TimeNs begin_ns = 0, end_ns = 0;
  std::string out_dir;
  bool progress = false;
  /// Set (e.g. by Ctrl-C) to stop early; what is done is written.
  const std::atomic<bool>* interrupted = nullptr;
};

struct OdometryRunResult {
  double data_s = 0.0, wall_s = 0.0;
  std::size_t poses = 0;
  bool interrupted = false;
  std::optional<TrajectoryEvaluation> accuracy;  ///< against the sequence's ground truth
  std::optional<eval::DepthErrorSummary> depth;  ///< depth/ against the ground-truth depth
};

Expected<OdometryRunResult> RunOdometry(const OdometryRunRequest& request, Context& ctx);

}  // namespace aavio::cli
