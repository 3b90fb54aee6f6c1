#include "aavio/eval/depth_error.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

namespace aavio::eval {
namespace {

bool OnDiscontinuity(const cv::Mat& depth_m, int x, int y) {
  float lo = depth_m.at<float>(y, x), hi = lo;
  for (int dy = -1; dy <= 1; ++dy) {
    const int yy = y + dy;
    if (yy < 0 || yy >= depth_m.rows) continue;
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = x + dx;
      if (xx < 0 || xx >= depth_m.cols) continue;
      const float z = depth_m.at<float>(yy, xx);
      if (z <= 0.0f) return true;  // next to the sky or an unrendered pixel
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  }
  return static_cast<double>(hi) > kDiscontinuityRatio * static_cast<double>(lo);
}

}  // namespace

void DepthErrorAccumulator::Add(const std::vector<Eigen::Vector3d>& points_world,
                                const cv::Mat& gt_depth_m, const cv::Mat& gt_edges,
                                const geometry::RigidTransform& T_world_cam) {
  ++frames_;
  const geometry::RigidTransform T_cam_world = T_world_cam.Inverse();
  cv::Mat covered(camera_.height, camera_.width, CV_8UC1, cv::Scalar(0));
  for (const Eigen::Vector3d& pw : points_world) {
    const Eigen::Vector3d p = T_cam_world * pw;
    if (p.z() <= 1e-6) continue;
    const double u = camera_.f * p.x() / p.z() + camera_.cx;
    const double v = camera_.f * p.y() / p.z() + camera_.cy;
    const int ui = static_cast<int>(std::lround(u)), vi = static_cast<int>(std::lround(v));
    if (ui < 0 || vi < 0 || ui >= camera_.width || vi >= camera_.height) continue;
    covered.at<std::uint8_t>(vi, ui) = 255;
    const double z_gt = gt_depth_m.at<float>(vi, ui);
    if (z_gt <= 0.0) continue;
    const double error = std::abs(p.z() - z_gt);
    errors_.push_back(error);
    relative_.push_back(error / z_gt);
    true_depth_sum_ += z_gt;
    if (camera_.fb_px_m > 0.0)
      disparity_errors_.push_back(camera_.fb_px_m * std::abs(1.0 / p.z() - 1.0 / z_gt));
    std::uint8_t kind = 0;
    if (!gt_edges.empty() && gt_edges.at<std::uint8_t>(vi, ui) == 255) {
      ++horizontal_points_;
      relative_horizontal_sum_ += error / z_gt;
      kind |= ScoredDepthPoint::kHorizontal;
    }
    for (std::size_t c = 0; c < kDepthCutoffsM.size(); ++c) {
      if (z_gt > kDepthCutoffsM[c]) continue;
      ++cutoffs_[c].points;
      cutoffs_[c].error_sum += error;
      cutoffs_[c].relative_sum += error / z_gt;
    }
    if (OnDiscontinuity(gt_depth_m, ui, vi)) {
      ++discontinuity_points_;
      relative_discontinuity_sum_ += error / z_gt;
      kind |= ScoredDepthPoint::kDiscontinuity;
    }
    if (keep_points_) {
      points_.push_back({static_cast<float>(u), static_cast<float>(v), static_cast<float>(z_gt),
                         static_cast<float>(p.z()), kind, static_cast<std::uint32_t>(frames_ - 1)});
    }
  }
  if (gt_edges.empty()) return;
  CountBlocks(covered, gt_edges);
  cv::dilate(covered, covered, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  for (int y = 0; y < camera_.height; ++y) {
    for (int x = 0; x < camera_.width; ++x) {
      const std::uint8_t label = gt_edges.at<std::uint8_t>(y, x);
      if (label == 0) continue;
      const bool hit = covered.at<std::uint8_t>(y, x) != 0;
      ++edges_;
      edges_covered_ += hit ? 1 : 0;
      if (label == 255) {
        ++horizontal_edges_;
        horizontal_covered_ += hit ? 1 : 0;
      }
      const double z_gt = gt_depth_m.at<float>(y, x);
      if (z_gt <= 0.0) continue;
      for (std::size_t c = 0; c < kDepthCutoffsM.size(); ++c) {
        if (z_gt > kDepthCutoffsM[c]) continue;
        CutoffCounts& k = cutoffs_[c];
        ++k.edges;
        k.edges_covered += hit ? 1 : 0;
        if (label == 255) {
          ++k.horizontal;
          k.horizontal_covered += hit ? 1 : 0;
        }
      }
    }
  }
}

void DepthErrorAccumulator::CountBlocks(const cv::Mat& covered, const cv::Mat& gt_edges) {
  constexpr int b = kCoverageBlockPx;
  for (int y0 = 0; y0 + b <= camera_.height; y0 += b) {
    for (int x0 = 0; x0 + b <= camera_.width; x0 += b) {
      const cv::Rect block(x0, y0, b, b);
      if (cv::countNonZero(gt_edges(block)) < b) continue;
      ++blocks_;
      blocks_covered_ += cv::countNonZero(covered(block)) > 0 ? 1 : 0;
    }
  }
}

DepthErrorSummary DepthErrorAccumulator::Summary() const {
  DepthErrorSummary s;
  s.frames = frames_;
  s.points = errors_.size();
  if (!errors_.empty()) {
    s.mean_m = std::accumulate(errors_.begin(), errors_.end(), 0.0) / errors_.size();
    std::vector<double> sorted = errors_;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    s.median_m = sorted[sorted.size() / 2];
    s.relative = std::accumulate(relative_.begin(), relative_.end(), 0.0) / relative_.size();
    std::vector<double> rel = relative_;
    std::nth_element(rel.begin(), rel.begin() + rel.size() / 2, rel.end());
    s.relative_median = rel[rel.size() / 2];
    s.mean_true_depth_m = true_depth_sum_ / errors_.size();
    s.outliers = static_cast<double>(std::count_if(relative_.begin(), relative_.end(),
                                                   [](double r) { return r > 0.1; })) /
                 relative_.size();
  }
  if (!disparity_errors_.empty()) {
    s.disparity_error_px =
        std::accumulate(disparity_errors_.begin(), disparity_errors_.end(), 0.0) /
        disparity_errors_.size();
    std::vector<double> d = disparity_errors_;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    s.disparity_error_median_px = d[d.size() / 2];
  }
  auto share = [](std::size_t a, std::size_t b) {
    return b == 0 ? 0.0 : static_cast<double>(a) / b;
  };
  s.completeness = share(edges_covered_, edges_);
  s.completeness_horizontal = share(horizontal_covered_, horizontal_edges_);
  s.completeness_other = share(edges_covered_ - horizontal_covered_, edges_ - horizontal_edges_);
  s.block_coverage = share(blocks_covered_, blocks_);
  s.points_horizontal = horizontal_points_;
  s.relative_horizontal =
      horizontal_points_ == 0 ? 0.0 : relative_horizontal_sum_ / horizontal_points_;
  s.points_discontinuity = discontinuity_points_;
  if (discontinuity_points_ > 0)
    s.relative_discontinuity = relative_discontinuity_sum_ / discontinuity_points_;
  if (s.points > discontinuity_points_) {
    s.relative_continuous =
        (s.relative * s.points - relative_discontinuity_sum_) / (s.points - discontinuity_points_);
  }
  for (std::size_t c = 0; c < kDepthCutoffsM.size(); ++c) {
    const CutoffCounts& k = cutoffs_[c];
    DepthCutoffSummary& out = s.cutoffs[c];
    out.max_depth_m = kDepthCutoffsM[c];
    out.points = k.points;
    if (k.points > 0) {
      out.mean_m = k.error_sum / k.points;
      out.relative = k.relative_sum / k.points;
    }
    out.completeness = share(k.edges_covered, k.edges);
    out.completeness_horizontal = share(k.horizontal_covered, k.horizontal);
  }
  return s;
}

}  // namespace aavio::eval
