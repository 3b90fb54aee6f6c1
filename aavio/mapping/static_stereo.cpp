#include "aavio/mapping/static_stereo.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "aavio/mapping/disparity_prediction.hpp"
#include "aavio/mapping/zncc.hpp"

namespace aavio::mapping {

DisparityRange StaticDisparityRange(const RectifiedStereo& stereo, InvDepthRange range) {
  DisparityRange r;
  r.min = std::max(0, static_cast<int>(std::floor(stereo.Disparity(range.min))));
  r.max = static_cast<int>(std::ceil(stereo.Disparity(range.max)));
  return r;
}

namespace {

// Share of the patch below 1 (an empty time surface there).
bool EmptyPatch(const float* top_left, int stride, int rows, int cols) {
  int low = 0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c)
      low += top_left[r * stride + c] < 1.0f ? 1 : 0;
  }
  return low > kEmptyPatchFraction * rows * cols;
}

// Left-right check (aavio): the right patch at u − d searched along the left row over the same
// disparity range must find its best match within `tolerance` of d.
bool LeftRightConsistent(const StaticStereoInput& in, int u, int v, int d,
                         const DisparityRange& range, int tolerance) {
  const int hw = kPatchWidth / 2, hh = kPatchHeight / 2;
  const int w = in.left.cols;
  const int stride = static_cast<int>(in.left.step1());
  const int x = u - d;  // the right patch's centre column
  NormalizedPatch patch;
  if (!PreparePatch(in.right.ptr<float>(v - hh) + (x - hw), stride, kPatchHeight, kPatchWidth,
                    &patch)) {
    return false;
  }
  // Left columns x + d' for d' in [d_lo, d_hi], the patch inside the image.
  const int d_lo = range.min, d_hi = std::min(range.max, w - 2 - hw - x);
  if (d_hi < d_lo) return false;
  const int count = d_hi - d_lo + 1;
  thread_local std::vector<double> back;
  back.resize(static_cast<std::size_t>(count));
  ZnccCostsAlongRow(patch, in.left.ptr<float>(v - hh) + (x + d_lo - hw), stride, count,
                    back.data());
  const auto best = std::min_element(back.begin(), back.end());
  const int best_back = d_lo + static_cast<int>(best - back.begin());
  return std::abs(best_back - d) <= tolerance;
}

// The best disparity of a prepared left patch at (u, v) along the right row over `range`, with
// its cost and the uniqueness test; false where the range leaves no right patch inside the image.
struct RowBest {
  double cost = 1.0;
  int d = -1;
  bool unique = true;
};
bool SearchRow(const StaticStereoInput& in, const NormalizedPatch& patch, int u, int v,
               const DisparityRange& range, double uniqueness, RowBest* out) {
  const int hw = kPatchWidth / 2, hh = kPatchHeight / 2;
  const int stride = static_cast<int>(in.left.step1());
  // Disparities whose right patch lies inside the image.
  const int d_lo = range.min, d_hi = std::min(range.max, u - hw - 1);
  if (d_hi < d_lo) return false;
  // All disparities at once: position j of the row search is disparity d_hi − j.
  const int count = d_hi - d_lo + 1;
  thread_local std::vector<double> along_row, costs;
  along_row.resize(static_cast<std::size_t>(count));
  ZnccCostsAlongRow(patch, in.right.ptr<float>(v - hh) + (u - d_hi - hw), stride, count,
                    along_row.data());
  costs.resize(static_cast<std::size_t>(count));
  *out = RowBest{};
  for (int d = d_lo; d <= d_hi; ++d) {
    const double e = along_row[static_cast<std::size_t>(d_hi - d)];
    costs[static_cast<std::size_t>(d - d_lo)] = e;
    if (e < out->cost) out->cost = e, out->d = d;
  }
  // Uniqueness: no other local minimum (beyond ±2 px) may come close to the best.
  if (uniqueness > 0.0 && out->d >= 0)
    out->unique = !HasRivalMinimum(costs.data(), count, out->d - d_lo, uniqueness);
  return true;
}

bool MatchOne(const StaticStereoInput& in, const Eigen::Vector2f& x, const RectifiedStereo& stereo,
              const StaticStereoConfig& c, InvDepthRange rho_range, const DisparityRange& full,
              const DisparityPrediction* prediction, Match* out) {
  const int hw = kPatchWidth / 2, hh = kPatchHeight / 2;
  const int u = static_cast<int>(std::lround(x.x())), v = static_cast<int>(std::lround(x.y()));
  const int w = in.left.cols, h = in.left.rows;
  // The patch may not touch the outermost rows/columns (bilinear access later).
  if (u - hw < 1 || u + hw > w - 2 || v - hh < 1 || v + hh > h - 2) return false;
  if (in.valid_mask.at<std::uint8_t>(v, u) <= 125) return false;
  const int stride = static_cast<int>(in.left.step1());
  const float* left = in.left.ptr<float>(v - hh) + (u - hw);
  if (EmptyPatch(left, stride, kPatchHeight, kPatchWidth)) return false;
  NormalizedPatch patch;
  if (!PreparePatch(left, stride, kPatchHeight, kPatchWidth, &patch)) return false;
  // The window the previous map predicts; the whole range where it predicts nothing or where the
  // window's best lies at a cut end (the curve still falling: the true minimum may be beyond).
  DisparityRange range = full;
  RowBest best;
  bool searched = false;
  if (prediction != nullptr && prediction->Window(x.x(), x.y(), full, &range) &&
      SearchRow(in, patch, u, v, range, c.uniqueness, &best)) {
    const bool cut_end = (best.d == range.min && range.min > full.min) ||
                         (best.d == range.max && range.max < full.max);
    searched = !cut_end;
  }
  if (!searched) {
    range = full;
    if (!SearchRow(in, patch, u, v, range, c.uniqueness, &best)) return false;
  }
  if (!best.unique) return false;
  if (best.d < 0 || best.cost > 1.02 * c.zncc_threshold) return false;
  if (c.left_right_tolerance_px >= 0 &&
      !LeftRightConsistent(in, u, v, best.d, range, c.left_right_tolerance_px)) {
    return false;
  }
  const double rho = stereo.InvDepthOfDisparity(best.d);
  if (!(rho > 0.0) || !rho_range.Contains(rho)) return false;
  *out = {x.x(), x.y(), rho, best.cost, StereoKind::kStatic, false};
  return true;
}

}  // namespace

std::vector<Match> MatchStatic(const StaticStereoInput& input,
                               std::span<const Eigen::Vector2f> points,
                               const RectifiedStereo& stereo, const StaticStereoConfig& config,
                               InvDepthRange rho_range, const DisparityPrediction* prediction) {
  const DisparityRange range = StaticDisparityRange(stereo, rho_range);
  std::vector<Match> results(points.size());
  std::vector<char> ok(points.size(), 0);
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    ok[i] = MatchOne(input, points[i], stereo, config, rho_range, range, prediction, &results[i])
                ? 1
                : 0;
  });
  std::vector<Match> matches;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (ok[i]) matches.push_back(results[i]);
  }
  return matches;
}

}  // namespace aavio::mapping
