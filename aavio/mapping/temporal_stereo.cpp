#include "aavio/mapping/temporal_stereo.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "aavio/mapping/disparity_prediction.hpp"
#include "aavio/mapping/static_stereo.hpp"
#include "aavio/mapping/zncc.hpp"

namespace aavio::mapping {

InvDepthRange TemporalInvDepthRange(const TemporalStereoConfig& t, InvDepthRange range) {
  return {std::max(range.min, 1.0 / t.max_depth_m), std::min(range.max, 1.0 / t.min_depth_m)};
}

double TriangulateDepth(const RectifiedStereo& stereo, const Eigen::Vector2d& x_now,
                        const Eigen::Vector2d& x_past, const geometry::RigidTransform& T_past_now) {
  // Rays in the current frame: a = λ r_now, b = c_past + μ R_now_past r_past.
  const Eigen::Vector3d r_now((x_now.x() - stereo.cx_left) / stereo.f,
                              (x_now.y() - stereo.cy) / stereo.f, 1.0);
  const Eigen::Vector3d r_past_local((x_past.x() - stereo.cx_left) / stereo.f,
                                     (x_past.y() - stereo.cy) / stereo.f, 1.0);
  const geometry::RigidTransform T_now_past = T_past_now.Inverse();
  const Eigen::Vector3d r_past = T_now_past.R * r_past_local;
  const Eigen::Vector3d c = T_now_past.t;
  // Least squares λ r_now − μ r_past = c.
  Eigen::Matrix<double, 3, 2> A;
  A.col(0) = r_now;
  A.col(1) = -r_past;
  const Eigen::Matrix2d AtA = A.transpose() * A;
  if (std::abs(AtA.determinant()) < 1e-12) return -1.0;
  const Eigen::Vector2d lm = AtA.ldlt().solve(A.transpose() * c);
  if (lm.x() <= 0.0 || lm.y() <= 0.0) return -1.0;
  return lm.x();  // r_now has z = 1, so λ is the depth
}

namespace {

// The best match of a prepared patch of the current AA map along the epipolar segment of the
// depth range in one past AA map, with its triangulated depth and that depth's change for one
// pixel of matching error along the segment.
struct SegmentMatch {
  double cost = 1.0;
  double z = 0.0;
  double dz_per_px = 0.0;
  bool at_far_end = false, at_near_end = false;  // the best is the segment's first or last step
};

// What became of a candidate; the order is TemporalMatchStats' (MatchTemporal counts by it).
// What one search needs: the section, the cost threshold, the configured range of inverse depth
// and the part of it the depth gate leaves to search.
struct Search {
  const TemporalStereoConfig& config;
  double max_cost;
  InvDepthRange range, search;
};

enum class Outcome : std::uint8_t {
  kMatched,
  kNoSegment,
  kNoMatch,
  kIllConditioned,
  kCheckRejected,
  kOutOfRange
};

// The epipolar segment of inverse depths [rho_lo, rho_hi]: the projections of its farthest and
// nearest depth; false if either is behind the partner camera.
bool Segment(const Eigen::Vector2f& x, double rho_lo, double rho_hi,
             const geometry::RigidTransform& T_past_now, const RectifiedStereo& stereo,
             double* u_far, double* v_far, double* u_near, double* v_near) {
  return stereo.Project(T_past_now * stereo.Backproject(x.x(), x.y(), rho_lo), u_far, v_far) &&
         stereo.Project(T_past_now * stereo.Backproject(x.x(), x.y(), rho_hi), u_near, v_near);
}

// `window`: the part of the searched inverse depths to look at (null: all of it); the parallax
// test is the whole segment's either way.
Outcome SearchSegment(const NormalizedPatch& patch, const cv::Mat& aa_past,
                      const geometry::RigidTransform& T_past_now, const Eigen::Vector2f& x,
                      const RectifiedStereo& stereo, const Search& search,
                      const InvDepthRange* window, SegmentMatch* out) {
  const TemporalStereoConfig& t = search.config;
  constexpr int hr = kTemporalPatchRows / 2, hc = kTemporalPatchCols / 2;
  const int w = aa_past.cols, h = aa_past.rows;
  const int stride = static_cast<int>(aa_past.step1());
  // The epipolar segment: projections of the farthest and the nearest allowed depth.
  double u_far, v_far, u_near, v_near;
  if (!Segment(x, search.search.min, search.search.max, T_past_now, stereo, &u_far, &v_far, &u_near,
               &v_near)) {
    return Outcome::kNoSegment;
  }
  // Too little parallax over the whole depth range: depth would be mostly quantisation noise.
  if (std::max(std::abs(u_near - u_far), std::abs(v_near - v_far)) < t.min_parallax_px)
    return Outcome::kNoSegment;
  if (window != nullptr &&
      !Segment(x, window->min, window->max, T_past_now, stereo, &u_far, &v_far, &u_near, &v_near)) {
    return Outcome::kNoSegment;
  }
  const double du = u_near - u_far, dv = v_near - v_far;
  const double length = std::max(std::abs(du), std::abs(dv));
  if (window != nullptr && !(length > 0.0)) return Outcome::kNoSegment;
  // One candidate per pixel along the segment's major axis, at whole pixels of it (so the steps
  // are uniform and the parabola below is unbiased); the other coordinate is rounded.
  const bool along_u = std::abs(du) >= std::abs(dv);
  const double major_far = along_u ? u_far : v_far, major_len = along_u ? du : dv;
  const double sign = major_len >= 0.0 ? 1.0 : -1.0;
  const double first = std::round(major_far);
  const int steps = static_cast<int>(std::floor(std::abs(major_far + major_len - first)));
  auto s_of = [&](double k) { return (first + sign * k - major_far) / major_len; };
  thread_local std::vector<double> costs;  // reused: one search at a time per thread
  costs.assign(static_cast<std::size_t>(steps + 1), 1.0);
  int best_k = -1;
  for (int k = 0; k <= steps; ++k) {
    const double s = s_of(k);
    const int uc = static_cast<int>(std::lround(u_far + s * du));
    const int vc = static_cast<int>(std::lround(v_far + s * dv));
    if (uc - hc < 0 || uc + hc >= w || vc - hr < 0 || vc + hr >= h) continue;
    const double e = ZnccCost(patch, aa_past.ptr<float>(vc - hr) + (uc - hc), stride);
    if (e <= 0.0) continue;  // exact zeros are ignored (reference)
    costs[static_cast<std::size_t>(k)] = e;
    if (best_k < 0 || e < costs[static_cast<std::size_t>(best_k)]) best_k = k;
  }
  if (best_k < 0) return Outcome::kNoSegment;  // the segment lies outside the image
  const double best = costs[static_cast<std::size_t>(best_k)];
  // [ICRA code]: a wide patch on AA maps is accepted below 3θ.
  if (best >= search.max_cost) return Outcome::kNoMatch;
  // Sub-sample position along the segment: the vertex of the parabola through the best cost and
  // its neighbours.
  double k_star = best_k;
  if (best_k > 0 && best_k < steps) {
    const double a = costs[static_cast<std::size_t>(best_k - 1)],
                 c = costs[static_cast<std::size_t>(best_k + 1)];
    const double curvature = a - 2.0 * best + c;
    if (curvature > 1e-9 && a < 1.0 && c < 1.0)
      k_star += std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
  }
  const double s_star = s_of(k_star);
  const Eigen::Vector2d best_x(u_far + s_star * du, v_far + s_star * dv);
  const double z = TriangulateDepth(stereo, {x.x(), x.y()}, best_x, T_past_now);
  if (z < t.min_depth_m || z > t.max_depth_m) return Outcome::kNoMatch;
  // The depth's change for one pixel of matching error along the segment.
  const double one_px = 1.0 / length;
  const Eigen::Vector2d dir(du, dv);
  const double z_a = TriangulateDepth(stereo, {x.x(), x.y()}, best_x - one_px * dir, T_past_now);
  const double z_b = TriangulateDepth(stereo, {x.x(), x.y()}, best_x + one_px * dir, T_past_now);
  // Rays that no longer meet one pixel away: unbounded sensitivity.
  const double dz_per_px = z_a <= 0.0 || z_b <= 0.0 ? std::numeric_limits<double>::infinity()
                                                    : 0.5 * std::abs(z_b - z_a);
  *out = {best, z, dz_per_px, best_k == 0, best_k == steps};
  return Outcome::kMatched;
}

// The inverse depths the previous map predicts at x, inside the searched ones; false: none.
bool PredictedWindow(const DisparityPrediction* prediction, const Eigen::Vector2f& x,
                     const RectifiedStereo& stereo, const InvDepthRange& search,
                     InvDepthRange* window) {
  if (prediction == nullptr) return false;
  DisparityRange d;
  if (!prediction->Window(x.x(), x.y(), StaticDisparityRange(stereo, search), &d)) return false;
  window->min = std::max(search.min, stereo.InvDepthOfDisparity(d.min));
  window->max = std::min(search.max, stereo.InvDepthOfDisparity(d.max));
  return window->min < window->max;
}

// A search in one past view: within the predicted window, then the whole segment where the
// window leaves the image or its best is at a cut end of the window (the true one may lie
// beyond).
Outcome SearchPredicted(const NormalizedPatch& patch, const cv::Mat& aa_past,
                        const geometry::RigidTransform& T_past_now, const Eigen::Vector2f& x,
                        const RectifiedStereo& stereo, const Search& s, const InvDepthRange* window,
                        SegmentMatch* out) {
  if (window != nullptr) {
    const Outcome found = SearchSegment(patch, aa_past, T_past_now, x, stereo, s, window, out);
    const bool cut_far = out->at_far_end && window->min > s.search.min;
    const bool cut_near = out->at_near_end && window->max < s.search.max;
    if (found == Outcome::kMatched ? !cut_far && !cut_near : found != Outcome::kNoSegment)
      return found;
  }
  return SearchSegment(patch, aa_past, T_past_now, x, stereo, s, nullptr, out);
}

Outcome MatchOne(const TemporalStereoInput& in, const Eigen::Vector2f& x,
                 const RectifiedStereo& stereo, const Search& s,
                 const DisparityPrediction* prediction, Match* out) {
  const TemporalStereoConfig& t = s.config;
  constexpr int hr = kTemporalPatchRows / 2, hc = kTemporalPatchCols / 2;
  const int w = in.aa_now.cols, h = in.aa_now.rows;
  const int u = static_cast<int>(std::lround(x.x())), v = static_cast<int>(std::lround(x.y()));
  if (u - hc < 0 || u + hc >= w || v - hr < 0 || v + hr >= h) return Outcome::kNoSegment;
  const int stride = static_cast<int>(in.aa_now.step1());
  const float* source = in.aa_now.ptr<float>(v - hr) + (u - hc);
  // A patch with (almost) nothing accumulated carries no structure.
  int empty = 0;
  for (int r = 0; r < kTemporalPatchRows; ++r) {
    for (int c = 0; c < kTemporalPatchCols; ++c)
      empty += source[r * stride + c] < 1.0f ? 1 : 0;
  }
  if (empty > kEmptyPatchFraction * kTemporalPatchRows * kTemporalPatchCols)
    return Outcome::kNoSegment;
  NormalizedPatch patch;
  if (!PreparePatch(source, stride, kTemporalPatchRows, kTemporalPatchCols, &patch))
    return Outcome::kNoSegment;

  InvDepthRange window;
  const InvDepthRange* predicted =
      PredictedWindow(prediction, x, stereo, s.search, &window) ? &window : nullptr;
  SegmentMatch m;
  const Outcome found =
      SearchPredicted(patch, in.aa_past, in.T_past_now, x, stereo, s, predicted, &m);
  if (found != Outcome::kMatched) return found;
  // Conditioning: one pixel of matching error may not move the depth by more than
  // max_relative_depth_error (parallax too small for this depth otherwise).
  const double max_error = t.max_relative_depth_error;
  if (max_error > 0.0 && !(m.dz_per_px / m.z <= max_error)) return Outcome::kIllConditioned;
  double rho = 1.0 / m.z;
  if (in.aa_check != nullptr) {
    // Cross-check (aavio): an independent search in a second, older view must find the same
    // depth within cross_check_px pixels of matching error (summed over both searches); then
    // the two are averaged in inverse depth, weighted by their per-pixel precision.
    SegmentMatch c;
    if (SearchPredicted(patch, *in.aa_check, *in.T_check_now, x, stereo, s, predicted, &c) !=
        Outcome::kMatched) {
      return Outcome::kCheckRejected;
    }
    const double d_rho_m = m.dz_per_px / (m.z * m.z), d_rho_c = c.dz_per_px / (c.z * c.z);
    const double rho_c = 1.0 / c.z;
    // Both precisions finite and non-zero (a zero one would take all the weight).
    if (!(d_rho_m > 0.0 && d_rho_c > 0.0 && std::isfinite(d_rho_m) && std::isfinite(d_rho_c)))
      return Outcome::kCheckRejected;
    if (std::abs(rho - rho_c) > t.cross_check_px * (d_rho_m + d_rho_c))
      return Outcome::kCheckRejected;
    const double w_m = 1.0 / (d_rho_m * d_rho_m), w_c = 1.0 / (d_rho_c * d_rho_c);
    rho = (w_m * rho + w_c * rho_c) / (w_m + w_c);
  }
  if (!s.range.Contains(rho)) return Outcome::kOutOfRange;
  *out = {x.x(), x.y(), rho, m.cost, StereoKind::kTemporal, true};
  return Outcome::kMatched;
}

}  // namespace

std::vector<Match> MatchTemporal(const TemporalStereoInput& input,
                                 std::span<const Eigen::Vector2f> points,
                                 const RectifiedStereo& stereo, const TemporalStereoConfig& config,
                                 double zncc_threshold, InvDepthRange range,
                                 TemporalMatchStats* stats, const DisparityPrediction* prediction) {
  // [ICRA code]: a wide patch on AA maps is accepted below 3θ.
  const Search search{config, 3.0 * zncc_threshold, range, TemporalInvDepthRange(config, range)};
  std::vector<Match> results(points.size());
  // An empty depth range (the gate outside the configured range) leaves nothing to search.
  std::vector<Outcome> outcomes(points.size(), Outcome::kNoSegment);
  if (search.search.min < search.search.max) {
    tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
      outcomes[i] = MatchOne(input, points[i], stereo, search, prediction, &results[i]);
    });
  }
  // Counted by outcome, in the order of both Outcome and TemporalMatchStats.
  std::array<int, 6> n{};
  std::vector<Match> matches;
  for (std::size_t i = 0; i < points.size(); ++i) {
    ++n[static_cast<std::size_t>(outcomes[i])];
    if (outcomes[i] == Outcome::kMatched) matches.push_back(results[i]);
  }
  static_assert(sizeof(TemporalMatchStats) == sizeof(n), "one count per outcome");
  if (stats != nullptr) *stats = {n[0], n[1], n[2], n[3], n[4], n[5]};
  return matches;
}

}  // namespace aavio::mapping
