#include "aavio/recording/run_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "aavio/common/format.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/ground_truth_depth.hpp"
#include "aavio/mapping/rectified_stereo.hpp"
#include "aavio/recording/depth_scorer.hpp"

namespace aavio::recording {
namespace {

nlohmann::json VelocityJson(const TrajectoryEvaluation& e) {
  const eval::VelocityError& v = e.velocity;
  return {{"pairs", v.pairs},
          {"auc", v.auc},
          {"rve_median", v.rve_median},
          {"linear_rmse_mps", v.linear_rmse_mps},
          {"angular_rmse_dps", v.angular_rmse_dps},
          {"gt_speed_median_mps", v.gt_speed_median_mps},
          {"estimate", e.velocity_from_estimate ? "given" : "derived"},
          {"ground_truth", e.velocity_from_ground_truth ? "given" : "derived"},
          {"half_window_s", NsToSeconds(e.options.velocity_half_window_ns)}};
}

nlohmann::json StatsJson(const eval::ErrorStatistics& s) {
  return {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},  {"std", s.std},
          {"min", s.min},   {"max", s.max},   {"samples", s.samples}};
}

// "up to 10 / 20 / 30 m: …" — where in depth the map reaches the scene.
std::string DepthCutoffLine(const eval::DepthErrorSummary& s) {
  std::string cut, rel, comp, horizontal;
  for (const eval::DepthCutoffSummary& c : s.cutoffs) {
    const char* sep = cut.empty() ? "" : " / ";
    cut += StrFormat("%s%.0f", sep, c.max_depth_m);
    rel += StrFormat("%s%.2f", sep, 100.0 * c.relative);
    comp += StrFormat("%s%.1f", sep, 100.0 * c.completeness);
    horizontal += StrFormat("%s%.1f", sep, 100.0 * c.completeness_horizontal);
  }
  return StrFormat(
      "  up to %s m of true depth: relative %s %%, completeness %s %% (near-horizontal "
      "edges %s %%)\n",
      cut.c_str(), rel.c_str(), comp.c_str(), horizontal.c_str());
}

// The estimated poses inside the ground truth's coverage: between two of its poses no further
// apart than 10 of its median intervals (motion capture that drops out leaves gaps).
std::size_t PosesWhereGroundTruthIs(const std::vector<geometry::StampedPose>& estimate,
                                    const std::vector<geometry::StampedPose>& ground_truth) {
  std::vector<TimeNs> steps;
  for (std::size_t i = 1; i < ground_truth.size(); ++i)
    steps.push_back(ground_truth[i].t_ns - ground_truth[i - 1].t_ns);
  if (steps.empty()) return 0;
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const TimeNs max_gap_ns = 10 * steps[steps.size() / 2];
  std::size_t covered = 0;
  for (const geometry::StampedPose& p : estimate) {
    auto after =
        std::lower_bound(ground_truth.begin(), ground_truth.end(), p.t_ns,
                         [](const geometry::StampedPose& g, TimeNs t) { return g.t_ns < t; });
    if (after == ground_truth.end()) continue;
    if (after->t_ns == p.t_ns) {
      ++covered;
      continue;
    }
    if (after == ground_truth.begin()) continue;
    if (after->t_ns - std::prev(after)->t_ns <= max_gap_ns) ++covered;
  }
  return covered;
}

}  // namespace

Expected<TrajectoryEvaluation> EvaluateTrajectories(
    const std::vector<geometry::StampedPose>& estimate,
    const std::vector<geometry::StampedPose>& ground_truth, const TrajectoryEvalOptions& options,
    const std::vector<geometry::StampedVelocity>* estimate_velocities,
    const std::vector<geometry::StampedVelocity>* gt_velocities) {
  AAVIO_RETURN_IF_ERROR(options.rpe.Validate());
  if (!(options.max_dt_s > 0.0 && options.max_dt_s < 10.0))
    return InvalidArgument(
        StrFormat("association window %g s: give a value in (0, 10) s", options.max_dt_s));
  if (estimate.empty()) return InvalidArgument("the estimate has no poses");
  if (ground_truth.size() < 2) return InvalidArgument("the ground truth has fewer than 2 poses");
  TrajectoryEvaluation e;
  e.options = options;
  Expected<std::vector<eval::PosePair>> pairs =
      eval::Associate(estimate, ground_truth, SecondsToNs(options.max_dt_s));
  if (!pairs) return pairs.status();
  if (pairs->size() < kMinPosePairs) {
    return InvalidArgument(StrFormat(
        "only %zu estimated pose(s) have a ground-truth pose within %g ms: a trajectory score "
        "needs at least %zu, so none is given (is the estimate this short, do the two "
        "trajectories barely overlap in time, or are their stamps in different units?)",
        pairs->size(), options.max_dt_s * 1e3, kMinPosePairs));
  }
  const std::size_t covered = PosesWhereGroundTruthIs(estimate, ground_truth);
  if (static_cast<double>(pairs->size()) < kMinMatchedShare * static_cast<double>(covered)) {
    return InvalidArgument(StrFormat(
        "only %zu of the %zu estimated poses where the ground truth has poses found one within "
        "%g ms (%.0f %%, under %.0f %%): the stamps do not line up, so no score is given (are "
        "both on the same clock and in the same unit? see --format and --max-dt)",
        pairs->size(), covered, options.max_dt_s * 1e3,
        100.0 * static_cast<double>(pairs->size()) / static_cast<double>(covered),
        100.0 * kMinMatchedShare));
  }
  e.pairs = std::move(*pairs);
  for (std::size_t i = 1; i < ground_truth.size(); ++i)
    e.gt_path_length_m +=
        (ground_truth[i].T_world_body.t - ground_truth[i - 1].T_world_body.t).norm();
  e.absolute = eval::EvaluateTrajectory(e.pairs, options.alignment, options.rpe_step_s,
                                        options.align_frames);
  e.relative = eval::ComputeRelativeError(e.pairs, e.gt_path_length_m, e.absolute.alignment.scale,
                                          options.rpe);
  e.velocity_from_estimate = estimate_velocities && estimate_velocities->size() == estimate.size();
  e.velocity_from_ground_truth = gt_velocities && gt_velocities->size() == ground_truth.size();
  const TimeNs window = options.velocity_half_window_ns;
  e.velocity = eval::EvaluateVelocities(
      e.velocity_from_estimate ? *estimate_velocities
                               : geometry::EstimateVelocities(estimate, window),
      e.velocity_from_ground_truth ? *gt_velocities
                                   : geometry::EstimateVelocities(ground_truth, window),
      SecondsToNs(options.max_dt_s));
  return e;
}

Expected<RunGroundTruth> RunGroundTruth::Of(const io::SequenceDescription& d,
                                            const geometry::StereoRig& rig) {
  if (!d.gt_trajectory) {
    return InvalidArgument(d.origin +
                           ": names no ground_truth.trajectory, so there is nothing "
                           "to evaluate against (use --est/--gt with a file of yours)");
  }
  RunGroundTruth truth;
  truth.sequence = d.origin;
  truth.trajectory = *d.gt_trajectory;
  truth.depth_dir = d.gt_depth;
  const mapping::RectifiedStereo stereo = mapping::RectifiedStereo::FromRig(rig);
  truth.camera = {stereo.width, stereo.height, stereo.f, stereo.cx_left, stereo.cy, stereo.fb()};
  truth.fb = stereo.fb();
  truth.disparity_offset = stereo.cx_left - stereo.cx_right;
  if (!d.gt_calibration.empty()) {
    const std::string context = d.origin + ": ground_truth.calibration " + d.gt_calibration;
    Expected<io::LoadedCalibration> true_calibration = io::LoadCalibration(d.gt_calibration);
    if (!true_calibration) return true_calibration.status().WithContext(context);
    Expected<geometry::CalibrationDifference> error =
        geometry::CompareCalibrations(rig, true_calibration->rig);
    if (!error) return error.status().WithContext(context);
    truth.calibration_error = *error;
  }
  return truth;
}

nlohmann::json CalibrationDifferenceJson(const geometry::CalibrationDifference& d) {
  return {{"disparity_offset_px", d.disparity_offset_px},
          {"disparity_offset_min_px", d.disparity_offset_min_px},
          {"disparity_offset_max_px", d.disparity_offset_max_px},
          {"row_offset_px", d.row_offset_px},
          {"max_row_offset_px", d.max_row_offset_px},
          {"fb_ratio", d.fb_ratio},
          {"directions", d.directions}};
}

std::string CalibrationDifferenceLine(const geometry::CalibrationDifference& d, double fb,
                                      const std::string& what) {
  // A point of true disparity 10 px is put at fb·r / (10 + ε) instead of fb / 10 (r: fb_ratio).
  constexpr double kDisparityPx = 10.0;
  std::string line =
      what +
      StrFormat(
          ": disparity at infinity "
          "%+.2f px (%+.2f to %+.2f over the view), rows %+.2f px (at most %.2f), f·b %+.2f %%",
          d.disparity_offset_px, d.disparity_offset_min_px, d.disparity_offset_max_px,
          d.row_offset_px, d.max_row_offset_px, 100.0 * (d.fb_ratio - 1.0));
  if (kDisparityPx + d.disparity_offset_px > 0.0) {  // else such a point gets no depth
    const double short_percent =
        100.0 * (1.0 - d.fb_ratio * kDisparityPx / (kDisparityPx + d.disparity_offset_px));
    line += StrFormat("; at %.0f px of disparity (%.1f m) depths %.1f %% %s", kDisparityPx,
                      fb / kDisparityPx, std::abs(short_percent),
                      short_percent >= 0.0 ? "short" : "long");
  }
  return line + "\n";
}

Expected<eval::DepthErrorAccumulator> EvaluateRunDepth(
    const std::string& estimate_dir, const RunGroundTruth& truth,
    const std::vector<geometry::StampedPose>& gt_poses, std::vector<io::GtDepthEntry>* scored) {
  Expected<DepthScorer> scorer = DepthScorer::Create(truth, gt_poses);
  if (!scorer) return scorer.status();
  if (scored) {
    scored->clear();
    scorer->KeepPoints(true);
  }
  Expected<std::vector<io::GtDepthEntry>> estimates = io::ReadGtDepthIndex(estimate_dir);
  if (!estimates) return estimates.status();
  for (const io::GtDepthEntry& est : *estimates) {
    Expected<io::GtDepthFrame> estimate =
        io::LoadGtDepthFrame(estimate_dir, est, truth.fb, truth.disparity_offset);
    if (!estimate) return estimate.status();
    Expected<bool> added = scorer->AddDepthImage(est.t_ns, estimate->depth_m);
    if (!added) {
      return added.status().WithContext(
          StrFormat("%s/disparity_%s.png", estimate_dir.c_str(), est.index.c_str()));
    }
    if (*added && scored) scored->push_back(est);
  }
  if (scorer->accumulator().Summary().frames == 0) {
    return InvalidArgument(estimate_dir + ": no depth map has a ground-truth frame of " +
                           truth.depth_dir +
                           " within 25 ms (are they of the same sequence and clock?)");
  }
  return scorer->accumulator();
}

nlohmann::json TrajectoryEvaluationJson(const TrajectoryEvaluation& e) {
  const eval::TrajectoryError& a = e.absolute;
  nlohmann::json rpe = nlohmann::json::array();
  for (const eval::SubTrajectoryErrors& s : e.relative.per_length) {
    rpe.push_back({{"length_m", s.length_m},
                   {"samples", s.trans_m.size()},
                   {"trans_m", StatsJson(s.trans_m_stats)},
                   {"trans_pct", StatsJson(s.trans_pct_stats)},
                   {"rot_deg", StatsJson(s.rot_deg_stats)},
                   {"rot_deg_per_m", StatsJson(s.rot_deg_per_m_stats)},
                   {"yaw_deg", StatsJson(s.yaw_deg_stats)}});
  }
  return {
      {"align", eval::AlignmentName(e.options.alignment)},
      {"align_frames", e.options.align_frames},
      {"scale", a.alignment.scale},
      {"pairs", a.pairs},
      {"path_length_m", e.gt_path_length_m},
      {"matched_path_length_m", a.path_length_m},
      {"ate_rmse_m", a.ate_rmse_m},
      {"ate_mean_m", a.ate_mean_m},
      {"ate_median_m", a.ate_median_m},
      {"ate_max_m", a.ate_max_m},
      {"ate_percent_of_path", a.path_length_m > 0.0 ? 100.0 * a.ate_rmse_m / a.path_length_m : 0.0},
      {"ate_rot_rmse_deg", a.ate_rotation_rmse_deg},
      {"alignment_rotation_sigma_deg", a.alignment_rotation_sigma_deg},
      {"ate_rot_rmse_orientation_aligned_deg", a.ate_rotation_rmse_orientation_aligned_deg},
      {"rpe_trans_pct", e.relative.trans_pct_rmse},
      {"rpe_rot_deg_per_m", e.relative.rot_deg_per_m_rmse},
      {"rpe_samples", e.relative.samples},
      {"rpe", rpe},
      {"rpe_step_s", a.rpe_step_s},
      {"rpe_step_trans_rmse_m", a.rpe_translation_rmse_m},
      {"rpe_step_rot_rmse_deg", a.rpe_rotation_rmse_deg},
      {"velocity", VelocityJson(e)}};
}

nlohmann::json CoverageJson(const eval::DepthErrorSummary& s) {
  return {{"completeness", s.completeness},
          {"completeness_near_horizontal", s.completeness_horizontal},
          {"completeness_other", s.completeness_other},
          {"block_coverage", s.block_coverage}};
}

nlohmann::json DepthJson(const eval::DepthErrorSummary& s) {
  nlohmann::json j = CoverageJson(s);
  j.update(nlohmann::json{{"mean_m", s.mean_m},
                          {"median_m", s.median_m},
                          {"relative", s.relative},
                          {"relative_median", s.relative_median},
                          {"outliers_over_10pct", s.outliers},
                          {"mean_true_depth_m", s.mean_true_depth_m},
                          {"disparity_error_px", s.disparity_error_px},
                          {"disparity_error_median_px", s.disparity_error_median_px},
                          {"points", s.points},
                          {"points_near_horizontal", s.points_horizontal},
                          {"relative_near_horizontal", s.relative_horizontal},
                          {"points_on_discontinuities", s.points_discontinuity},
                          {"relative_on_discontinuities", s.relative_discontinuity},
                          {"relative_off_discontinuities", s.relative_continuous},
                          {"frames", s.frames}});
  nlohmann::json cutoffs = nlohmann::json::array();
  for (const eval::DepthCutoffSummary& c : s.cutoffs) {
    cutoffs.push_back({{"max_depth_m", c.max_depth_m},
                       {"points", c.points},
                       {"mean_m", c.mean_m},
                       {"relative", c.relative},
                       {"completeness", c.completeness},
                       {"completeness_near_horizontal", c.completeness_horizontal}});
  }
  j["cutoffs"] = cutoffs;
  return j;
}

bool RotationErrorIsTheAlignments(const eval::TrajectoryError& a) {
  return a.alignment_rotation_sigma_deg >= kMinAlignmentSigmaDeg &&
         a.alignment_rotation_sigma_deg >= 0.5 * a.ate_rotation_rmse_deg;
}

std::string TrajectoryEvaluationTable(const TrajectoryEvaluation& e) {
  const eval::TrajectoryError& a = e.absolute;
  std::string s = StrFormat(
      "%zu pose pairs (within %.0f ms), aligned %s%s, ground-truth path %.3f m (%.3f m matched)\n",
      a.pairs, 1e3 * e.options.max_dt_s, eval::AlignmentName(e.options.alignment),
      e.options.alignment == eval::Alignment::kSim3
          ? StrFormat(" (scale %.4f)", a.alignment.scale).c_str()
          : "",
      e.gt_path_length_m, a.path_length_m);
  s += StrFormat(
      "ATE  rmse %.4f m (%.2f %% of the path)  mean %.4f  median %.4f  max %.4f m  "
      "rotation rmse %.3f deg\n",
      a.ate_rmse_m, a.path_length_m > 0 ? 100.0 * a.ate_rmse_m / a.path_length_m : 0.0,
      a.ate_mean_m, a.ate_median_m, a.ate_max_m, a.ate_rotation_rmse_deg);
  if (RotationErrorIsTheAlignments(a)) {
    s += StrFormat(
        "     warning: the path is too short or too straight to fix the alignment's rotation\n"
        "     (uncertain by ~%.0f deg: the ATE over the positions' spread across the path), so "
        "the\n"
        "     rotation error above mostly measures the alignment; with the orientations aligned\n"
        "     alone it is %.3f deg\n",
        a.alignment_rotation_sigma_deg, a.ate_rotation_rmse_orientation_aligned_deg);
  }
  s += StrFormat(
      "RPE  (ESVO papers' form, rmse over %zu sub-trajectories) translation %.3f %%  "
      "rotation %.4f deg/m\n",
      e.relative.samples, e.relative.trans_pct_rmse, e.relative.rot_deg_per_m_rmse);
  s += "RPE  (rpg_trajectory_evaluation form, per sub-trajectory length; median [rmse])\n";
  s += "     length [m]  samples   trans [m]            trans [%]          rot [deg]          "
       "yaw [deg]\n";
  for (const eval::SubTrajectoryErrors& r : e.relative.per_length) {
    s += StrFormat(
        "     %10.2f  %7zu   %8.4f [%8.4f]  %7.3f [%7.3f]  %7.3f [%7.3f]  %7.3f [%7.3f]\n",
        r.length_m, r.trans_m.size(), r.trans_m_stats.median, r.trans_m_stats.rmse,
        r.trans_pct_stats.median, r.trans_pct_stats.rmse, r.rot_deg_stats.median,
        r.rot_deg_stats.rmse, r.yaw_deg_stats.median, r.yaw_deg_stats.rmse);
  }
  s += StrFormat("RPE  over %.2f s steps: translation rmse %.4f m, rotation rmse %.4f deg\n",
                 a.rpe_step_s, a.rpe_translation_rmse_m, a.rpe_rotation_rmse_deg);
  const eval::VelocityError& v = e.velocity;
  if (v.pairs > 0) {
    const std::string how =
        e.velocity_from_estimate && e.velocity_from_ground_truth
            ? "as the files give them"
            : StrFormat(
                  "%s from the poses over +-%.0f ms",
                  e.velocity_from_estimate || e.velocity_from_ground_truth ? "partly" : "derived",
                  NsToMs(e.options.velocity_half_window_ns));
    s += StrFormat(
        "VEL  (body frame, %s; %zu pairs, true speed median %.3f m/s) EvSLAM AUC %.3f, relative "
        "error median %.1f %%, rmse %.3f m/s, %.2f deg/s\n",
        how.c_str(), v.pairs, v.gt_speed_median_mps, v.auc, 100.0 * v.rve_median, v.linear_rmse_mps,
        v.angular_rmse_dps);
  }
  return s;
}

std::string DepthTable(const eval::DepthErrorSummary& s) {
  const std::string overall = StrFormat(
      "depth (%zu points over %zu maps, true depth %.1f m on average): mean %.3f m, median %.3f m, "
      "relative %.2f %% (median %.2f %%, %.1f %% of points > 10 %% off; %.2f %% on the %.1f %% of "
      "points at depth discontinuities, %.2f %% elsewhere); disparity error %.2f px (median "
      "%.2f px); completeness %.1f %% (near-horizontal edges %.1f %%, others %.1f %%), %.1f %% "
      "of the blocks with edges reached\n",
      s.points, s.frames, s.mean_true_depth_m, s.mean_m, s.median_m, 100.0 * s.relative,
      100.0 * s.relative_median, 100.0 * s.outliers, 100.0 * s.relative_discontinuity,
      s.points > 0 ? 100.0 * s.points_discontinuity / s.points : 0.0, 100.0 * s.relative_continuous,
      s.disparity_error_px, s.disparity_error_median_px, 100.0 * s.completeness,
      100.0 * s.completeness_horizontal, 100.0 * s.completeness_other, 100.0 * s.block_coverage);
  return overall + DepthCutoffLine(s);
}

std::string SampleCeilingLine(const eval::DepthErrorSummary& c) {
  return StrFormat(
      "edge samples at their true depth would cover %.1f %% (near-horizontal edges %.1f %%, others "
      "%.1f %%), %.1f %% of the blocks with edges (depth.sample_ceiling)\n",
      100.0 * c.completeness, 100.0 * c.completeness_horizontal, 100.0 * c.completeness_other,
      100.0 * c.block_coverage);
}

}  // namespace aavio::recording
