#include "aavio/mapping/sgm_bootstrap.hpp"

#include <cmath>
#include <opencv2/calib3d.hpp>

#include "aavio/common/format.hpp"
#include "aavio/mapping/depth_map.hpp"
#include "aavio/mapping/static_stereo.hpp"

namespace aavio::mapping {

Expected<std::vector<DepthPoint>> BootstrapWithSgm(const cv::Mat& ts_left, const cv::Mat& ts_right,
                                                   std::span<const Eigen::Vector2f> points,
                                                   const RectifiedStereo& stereo,
                                                   double student_t_nu, InvDepthRange rho_range) {
  const DisparityRange range = StaticDisparityRange(stereo, rho_range);
  // OpenCV searches [min, min + n) with n a positive multiple of 16, and finds nothing left of
  // column min + n. From 0 to the nearest depth's disparity while that leaves half the image;
  // a wider rig's search (a 60 cm baseline at 1 m: 120 px on a 240 px image) starts at the far
  // end of the depth range and spans half the width, nearer points left to the mapping cycles.
  const int half_width = std::max(16, stereo.width / 2 / 16 * 16);
  int min_disparity = 0;
  int disparities = std::max(16, (range.max + 15) / 16 * 16);
  if (disparities > half_width) {
    min_disparity = std::max(0, range.min);
    disparities = std::min(half_width, std::max(16, (range.max - min_disparity + 16) / 16 * 16));
  }
  constexpr int kBlock = 11, kUniquenessRatio = 11;
  constexpr int kArea = kBlock * kBlock;
  cv::Ptr<cv::StereoSGBM> sgm =
      cv::StereoSGBM::create(min_disparity, disparities, kBlock, 8 * kArea, 32 * kArea,
                             /*disp12MaxDiff=*/-1,
                             /*preFilterCap=*/0, kUniquenessRatio, /*speckleWindowSize=*/0,
                             /*speckleRange=*/0, cv::StereoSGBM::MODE_SGBM);
  cv::Mat disparity;  // CV_16S, disparity × 16
  sgm->compute(ts_left, ts_right, disparity);
  const double sigma2 = kSgmInvDepthStddev * kSgmInvDepthStddev;
  const double nu = student_t_nu;
  std::vector<DepthPoint> out;
  std::vector<char> taken(static_cast<std::size_t>(stereo.width) * stereo.height, 0);
  for (const Eigen::Vector2f& x : points) {
    const int u = static_cast<int>(std::floor(x.x())), v = static_cast<int>(std::floor(x.y()));
    if (u < 0 || v < 0 || u >= stereo.width || v >= stereo.height) continue;
    char& t = taken[static_cast<std::size_t>(v) * stereo.width + u];
    if (t) continue;
    t = 1;
    const short d16 = disparity.at<short>(v, u);
    if (d16 < min_disparity * 16 || d16 <= 0) continue;  // invalid, or infinitely far
    const double rho = stereo.InvDepthOfDisparity(d16 / 16.0);
    if (!rho_range.Contains(rho)) continue;
    DepthPoint p;
    p.u = static_cast<float>(u);
    p.v = static_cast<float>(v);
    p.rho = rho;
    p.nu = nu;
    p.s2 = sigma2 * (nu - 2.0) / nu;
    p.residual = 0.0;
    p.age = kMinAge;  // survives the first cleanings
    out.push_back(p);
  }
  return out;
}

}  // namespace aavio::mapping
