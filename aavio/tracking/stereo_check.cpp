#include "aavio/tracking/stereo_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "aavio/mapping/static_stereo.hpp"
#include "aavio/mapping/zncc.hpp"

namespace aavio::tracking {
namespace {

constexpr int kHalfW = mapping::kPatchWidth / 2, kHalfH = mapping::kPatchHeight / 2;
// Disparities this close to the point's own [px] are its own: a match there is not elsewhere.
constexpr double kOwnDisparityPx = 2.0;
// The point's own disparity matches at up to this many times θ: time surfaces of the two cameras
// differ more than the frames static stereo matches did when the map was made (events since).
constexpr double kOwnTolerance = 2.0;

// Rows [v − h, v + h] of columns [x0, x0 + width) of an 8-bit image, as floats (stride width).
void CopyStrip(const cv::Mat& image, int v, int x0, int width, std::vector<float>* out) {
  out->resize(static_cast<std::size_t>(width * mapping::kPatchHeight));
  for (int r = 0; r < mapping::kPatchHeight; ++r) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(v - kHalfH + r) + x0;
    float* dst = out->data() + static_cast<std::ptrdiff_t>(r) * width;
    for (int c = 0; c < width; ++c)
      dst[c] = static_cast<float>(row[c]);
  }
}

// Sums of a 15×7 patch of an 8-bit image (exact, in integers).
struct PatchSums {
  std::int64_t sum = 0, sq = 0;
  int zeros = 0;
};
PatchSums SumsOf(const cv::Mat& image, int u, int v) {
  PatchSums s;
  for (int r = -kHalfH; r <= kHalfH; ++r) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(v + r) + (u - kHalfW);
    int sum = 0, sq = 0, zeros = 0;
    for (int c = 0; c < mapping::kPatchWidth; ++c) {
      sum += row[c];
      sq += row[c] * row[c];
      zeros += row[c] == 0 ? 1 : 0;
    }
    s.sum += sum, s.sq += sq, s.zeros += zeros;
  }
  return s;
}

// ½(1 − ZNCC) of the left patch at (u, v) against the right patch at (x, v), from exact integer
// sums: mapping::ZnccCostFromSums's rules (0.5 for a flat patch or means a factor of 5 apart).
double OwnCost(const cv::Mat& left, const PatchSums& a, const cv::Mat& right, int u, int x,
               int v) {
  std::int64_t sum_b = 0, sq_b = 0, cross = 0;
  for (int r = -kHalfH; r <= kHalfH; ++r) {
    const std::uint8_t* la = left.ptr<std::uint8_t>(v + r) + (u - kHalfW);
    const std::uint8_t* rb = right.ptr<std::uint8_t>(v + r) + (x - kHalfW);
    int s = 0, q = 0, ab = 0;
    for (int c = 0; c < mapping::kPatchWidth; ++c) {
      s += rb[c];
      q += rb[c] * rb[c];
      ab += la[c] * rb[c];
    }
    sum_b += s, sq_b += q, cross += ab;
  }
  constexpr std::int64_t n = mapping::kPatchWidth * mapping::kPatchHeight;
  // n² times the variances and the covariance, exactly.
  const std::int64_t var_a = n * a.sq - a.sum * a.sum, var_b = n * sq_b - sum_b * sum_b;
  if (var_a <= 0 || var_b <= 0) return 0.5;
  if (a.sum > 5 * sum_b || sum_b > 5 * a.sum) return 0.5;
  const double cov = static_cast<double>(n * cross - a.sum * sum_b);
  return 0.5 * (1.0 - cov / std::sqrt(static_cast<double>(var_a) * static_cast<double>(var_b)));
}

}  // namespace

StereoCheck::StereoCheck(const cv::Mat& left_ts, const cv::Mat& right_ts, const cv::Mat& valid_mask,
                         const Camera& camera, const StereoCheckRig& rig)
    : left_(left_ts), right_(right_ts), valid_mask_(valid_mask), camera_(camera), rig_(rig) {}

bool StereoCheck::SeesSomethingElse(const Eigen::Vector3d& q_cam) const {
  if (q_cam.z() <= 1e-6 || right_.size() != left_.size() || valid_mask_.size() != left_.size())
    return false;
  const int u = static_cast<int>(std::lround(camera_.f * q_cam.x() / q_cam.z() + camera_.cx));
  const int v = static_cast<int>(std::lround(camera_.f * q_cam.y() / q_cam.z() + camera_.cy));
  if (u - kHalfW < 0 || u + kHalfW >= left_.cols || v - kHalfH < 0 || v + kHalfH >= left_.rows)
    return false;
  if (valid_mask_.at<std::uint8_t>(v, u) <= 125) return false;
  // The left patch: no events there, nothing to tell.
  const PatchSums a = SumsOf(left_, u, v);
  if (a.zeros > mapping::kEmptyPatchFraction * mapping::kPatchWidth * mapping::kPatchHeight)
    return false;
  // The disparities whose right patch lies inside the image.
  const int d_lo = std::max(rig_.min_disparity, u + kHalfW - (right_.cols - 1));
  const int d_hi = std::min(rig_.max_disparity, u - kHalfW);
  if (d_hi < d_lo) return false;
  // The point's own disparity, held near the range (a point nearer than it has none there).
  const double d = std::clamp(rig_.fb / q_cam.z() + rig_.disparity_offset, d_lo - 4.0, d_hi + 4.0);
  const int own_lo = std::max(d_lo, static_cast<int>(std::floor(d)) - 1);
  const int own_hi = std::min(d_hi, static_cast<int>(std::ceil(d)) + 1);
  // Its own disparity first (a few comparisons, on the 8-bit images): a match there, and it
  // stays. Most points end here.
  double own = 1.0;
  for (int k = own_lo; k <= own_hi; ++k)
    own = std::min(own, OwnCost(left_, a, right_, u, u - k, v));
  if (own_lo <= own_hi && own <= kOwnTolerance * rig_.zncc_threshold) return false;
  // The row (the float patch static stereo compares): a match static stereo would accept, away
  // from the point's own disparity.
  thread_local std::vector<float> left, strip;
  CopyStrip(left_, v, u - kHalfW, mapping::kPatchWidth, &left);
  mapping::NormalizedPatch patch;
  if (!mapping::PreparePatch(left.data(), mapping::kPatchWidth, mapping::kPatchHeight,
                             mapping::kPatchWidth, &patch))
    return false;
  const int count = d_hi - d_lo + 1;
  const int width = count + mapping::kPatchWidth - 1;
  CopyStrip(right_, v, u - d_hi - kHalfW, width, &strip);
  thread_local std::vector<double> costs;
  costs.resize(static_cast<std::size_t>(count));
  mapping::ZnccCostsAlongRow(patch, strip.data(), width, count, costs.data());
  for (int j = 0; j < count; ++j) {
    const int k = d_hi - j;  // costs[j]: the right patch at disparity d_hi − j
    if (std::abs(k - d) > kOwnDisparityPx &&
        costs[static_cast<std::size_t>(j)] <= rig_.zncc_threshold)
      return true;
  }
  return false;
}

}  // namespace aavio::tracking
