#include "aavio/mapping/edge_snapping.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace aavio::mapping {
namespace {

double Bilinear(const cv::Mat& image, double x, double y) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double ax = x - x0, ay = y - y0;
  const auto at = [&](int yy, int xx) {
    return static_cast<double>(image.at<std::uint8_t>(yy, xx));
  };
  return (1 - ay) * ((1 - ax) * at(y0, x0) + ax * at(y0, x0 + 1)) +
         ay * ((1 - ax) * at(y0 + 1, x0) + ax * at(y0 + 1, x0 + 1));
}

}  // namespace

void SnapToNewestEdge(const cv::Mat& negative_ts, const cv::Mat& grad_u, const cv::Mat& grad_v,
                      double max_px, std::vector<events::EdgeSample>* samples) {
  constexpr double kStep = 0.25;
  const int n = static_cast<int>(std::floor(max_px / kStep));
  if (n <= 0) return;
  std::vector<double> profile(static_cast<std::size_t>(2 * n + 1));
  for (events::EdgeSample& s : *samples) {
    const double u = static_cast<double>(s.u), v = static_cast<double>(s.v);
    const int ui = static_cast<int>(std::lround(u)), vi = static_cast<int>(std::lround(v));
    if (ui < 0 || vi < 0 || ui >= negative_ts.cols || vi >= negative_ts.rows) continue;
    const double gu = grad_u.at<float>(vi, ui), gv = grad_v.at<float>(vi, ui);
    const double norm = std::hypot(gu, gv);
    if (!(norm >= 1.0)) continue;
    const double du = gu / norm, dv = gv / norm;
    for (int k = -n; k <= n; ++k) {
      const double x = u + k * kStep * du, y = v + k * kStep * dv;
      const bool inside =
          x >= 0.0 && y >= 0.0 && x < negative_ts.cols - 1.0 && y < negative_ts.rows - 1.0;
      profile[static_cast<std::size_t>(k + n)] = inside ? Bilinear(negative_ts, x, y) : 256.0;
    }
    const auto lowest = std::min_element(profile.begin(), profile.end());
    const std::size_t best = static_cast<std::size_t>(lowest - profile.begin());
    double offset = static_cast<double>(best) - n;
    if (best > 0 && best + 1 < profile.size()) {
      const double a = profile[best - 1], b = profile[best], c = profile[best + 1];
      const double curvature = a - 2.0 * b + c;  // ≥ |a − c| at a minimum: the shift is ≤ ½ step
      if (curvature > 1e-9) offset += 0.5 * (a - c) / curvature;
    }
    s.u = static_cast<float>(u + offset * kStep * du);
    s.v = static_cast<float>(v + offset * kStep * dv);
  }
}

}  // namespace aavio::mapping
