#include "aavio/tracking/stereo_check.hpp"

#include <algorithm>
#include <cmath>
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
  thread_local std::vector<float> left, strip;
  CopyStrip(left_, v, u - kHalfW, mapping::kPatchWidth, &left);
  const auto empty = std::count(left.begin(), left.end(), 0.0f);
  if (static_cast<double>(empty) > mapping::kEmptyPatchFraction * static_cast<double>(left.size()))
    return false;
  mapping::NormalizedPatch patch;
  if (!mapping::PreparePatch(left.data(), mapping::kPatchWidth, mapping::kPatchHeight,
                             mapping::kPatchWidth, &patch))
    return false;
  // The disparities whose right patch lies inside the image.
  const int d_lo = std::max(rig_.min_disparity, u + kHalfW - (right_.cols - 1));
  const int d_hi = std::min(rig_.max_disparity, u - kHalfW);
  if (d_hi < d_lo) return false;
  // The point's own disparity, held near the range (a point nearer than it has none there).
  const double d = std::clamp(rig_.fb / q_cam.z() + rig_.disparity_offset, d_lo - 4.0, d_hi + 4.0);
  const int own_lo = std::max(d_lo, static_cast<int>(std::floor(d)) - 1);
  const int own_hi = std::min(d_hi, static_cast<int>(std::ceil(d)) + 1);
  // Its own disparity first (a few comparisons): a match there, and it stays.
  if (own_lo <= own_hi) {
    const int width = own_hi - own_lo + mapping::kPatchWidth;
    CopyStrip(right_, v, u - own_hi - kHalfW, width, &strip);
    double own = 1.0;
    for (int k = own_lo; k <= own_hi; ++k)
      own = std::min(own, mapping::ZnccCost(patch, strip.data() + (own_hi - k), width));
    if (own <= kOwnTolerance * rig_.zncc_threshold) return false;
  }
  // The row: a match static stereo would accept, away from the point's own disparity.
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
