#pragma once
/// What `aavio eval` computes and `aavio run` / `aavio report` reuse (docs/evaluation.md):
/// trajectory accuracy of an estimate against ground truth (association, alignment, ATE, the
/// distance-based RPE of rpg_trajectory_evaluation and its ESVO-paper summary, the per-tick RPE),
/// and depth accuracy of a run's depth maps (`depth/` of a run folder) against the sequence's
/// ground-truth depth.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/eval/depth_error.hpp"
#include "aavio/eval/relative_error.hpp"
#include "aavio/eval/trajectory_error.hpp"
#include "aavio/eval/velocity_error.hpp"
#include "aavio/geometry/calibration_difference.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/geometry/stereo_rig.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/io/sequence.hpp"

namespace aavio::recording {

struct TrajectoryEvalOptions {
  eval::Alignment alignment = eval::Alignment::kSe3;  ///< stereo VO: se3 (docs/evaluation.md)
  int align_frames = -1;                              ///< align on the first N pairs; −1 all
  double max_dt_s = 0.02;                             ///< association window
  double rpe_step_s = 0.1;                            ///< per-tick RPE (what `aavio run` prints)
  eval::RelativeErrorConfig rpe;
  /// Velocities not given with a trajectory are derived from its poses (geometry::
  /// EstimateVelocities) over this half window, the same for both so that they are compared at
  /// one bandwidth.
  TimeNs velocity_half_window_ns = geometry::kDefaultVelocityHalfWindowNs;
};

struct TrajectoryEvaluation {
  TrajectoryEvalOptions options;
  std::vector<eval::PosePair> pairs;
  double gt_path_length_m = 0.0;  ///< of the whole ground truth (the RPE lengths' reference)
  eval::TrajectoryError absolute;
  eval::RelativeError relative;
  eval::VelocityError velocity;         ///< EvSLAM's relative velocity error and its AUC
  bool velocity_from_estimate = false;  ///< the estimate gave its velocities (else derived)
  bool velocity_from_ground_truth = false;
};

/// Fewer pose pairs make no trajectory score; nor does matching under kMinMatchedShare of the
/// estimated poses that lie where the ground truth has poses (its span, without its gaps of
/// over 10 of its median intervals): a stamp unit or clock mix-up matches a few poses by chance.
inline constexpr std::size_t kMinPosePairs = 10;
inline constexpr double kMinMatchedShare = 0.5;

/// `estimate_velocities` / `gt_velocities`: the trajectories' own velocities, one per pose, if
/// their files hold them (EvSLAM's layout); otherwise derived from the poses.
Expected<TrajectoryEvaluation> EvaluateTrajectories(
    const std::vector<geometry::StampedPose>& estimate,
    const std::vector<geometry::StampedPose>& ground_truth, const TrajectoryEvalOptions& options,
    const std::vector<geometry::StampedVelocity>* estimate_velocities = nullptr,
    const std::vector<geometry::StampedVelocity>* gt_velocities = nullptr);

/// The ground truth a sequence names, as evaluating a run of it needs it.
struct RunGroundTruth {
  std::string sequence;                     ///< its sequence.yaml (or folder)
  io::SourceSpec trajectory;                ///< TUM or EuRoC text, or a bag's pose topic
  std::string depth_dir;                    ///< empty when the sequence has no ground-truth depth
  eval::PinholeCamera camera;               ///< the rectified left camera
  double fb = 0.0, disparity_offset = 0.0;  ///< for disparity-PNG ground truth (DSEC)
  /// The calibration's error against the true one, when the sequence names it
  /// (ground_truth.calibration: a simulated twin's).
  std::optional<geometry::CalibrationDifference> calibration_error;

  /// From a sequence's description and its calibration; an error says why there is nothing to
  /// evaluate against (no ground-truth trajectory), or that the true calibration is unreadable.
  static Expected<RunGroundTruth> Of(const io::SequenceDescription& sequence,
                                     const geometry::StereoRig& rig);
  /// The ground-truth poses (io::ReadGroundTruthPoses).
  Expected<std::vector<geometry::StampedPose>> ReadPoses() const {
    return io::ReadGroundTruthPoses(trajectory);
  }
  std::string trajectory_name() const { return io::DescribeSource(trajectory); }
};

/// Scores every depth map of `run_depth_dir` (`timestamps.txt` + `disparity_INDEX.png` or
/// `depth_INDEX.tiff`, the layout `aavio run` and `aavio simulate` share) as DepthScorer does.
/// With `scored`, the accumulator keeps its points (ScoredDepthPoint) and `scored` gets the maps
/// in the order they were scored: entry i is the points' frame i.
Expected<eval::DepthErrorAccumulator> EvaluateRunDepth(
    const std::string& run_depth_dir, const RunGroundTruth& truth,
    const std::vector<geometry::StampedPose>& gt_poses,
    std::vector<io::GtDepthEntry>* scored = nullptr);

/// Whether the ATE rotation error is mostly the alignment's: the positions leave its rotation
/// uncertain by at least half the error (eval::TrajectoryError::alignment_rotation_sigma_deg),
/// and by at least kMinAlignmentSigmaDeg. The table then says so.
inline constexpr double kMinAlignmentSigmaDeg = 0.1;
bool RotationErrorIsTheAlignments(const eval::TrajectoryError& a);

/// The `aavio eval --json` keys of docs/cli.md.
nlohmann::json TrajectoryEvaluationJson(const TrajectoryEvaluation& e);
nlohmann::json DepthJson(const eval::DepthErrorSummary& s);

/// summary.json "calibration_error", and the line `aavio run` ends with (`what`: what was
/// compared with what, "calibration against the true one (ground_truth.calibration)"; `fb`: the
/// compared calibration's f·b [px·m]).
nlohmann::json CalibrationDifferenceJson(const geometry::CalibrationDifference& d);
std::string CalibrationDifferenceLine(const geometry::CalibrationDifference& d, double fb,
                                      const std::string& what);

/// A readable table of the same.
std::string TrajectoryEvaluationTable(const TrajectoryEvaluation& e);
std::string DepthTable(const eval::DepthErrorSummary& s);
/// The coverage figures of a summary (completeness overall, near-horizontal and other; block
/// coverage), e.g. of an eval::SampleCeiling.
nlohmann::json CoverageJson(const eval::DepthErrorSummary& s);
/// One line: what the edge samples would cover at their true depth (eval::SampleCeiling).
std::string SampleCeilingLine(const eval::DepthErrorSummary& ceiling);

}  // namespace aavio::recording
