#include "aavio/pipeline/scene_depth_probe.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "aavio/mapping/sgm_bootstrap.hpp"
#include "aavio/pipeline/odometry_config.hpp"

namespace aavio::pipeline {
namespace {

// Fewer matched edges than this say nothing about the scene.
constexpr int kMinPoints = 50;
constexpr int kHalfSizeFromWidth = 600;
// Nearer edges are left out of the search (they would widen it past what the choice needs).
constexpr double kNearestM = 1.0;

events::RepresentationBuilder MakeBuilder(const geometry::StereoRig& rig, TimeNs start_ns) {
  return events::RepresentationBuilder(geometry::BuildStereoRectification(rig), rig.width(),
                                       rig.height(), RepresentationConfigOf(OdometryConfig{}),
                                       start_ns);
}

}  // namespace

double SceneDepth::ShareWithin(double near_m, double far_m) const {
  if (depths_m.empty()) return 0.0;
  const auto from = std::lower_bound(depths_m.begin(), depths_m.end(), near_m);
  const auto to = std::upper_bound(depths_m.begin(), depths_m.end(), far_m);
  return to > from ? static_cast<double>(to - from) / static_cast<double>(depths_m.size()) : 0.0;
}

SceneDepthProbe::SceneDepthProbe(const geometry::StereoRig& rig, TimeNs start_ns)
    : rig_(rig), start_ns_(start_ns), builder_(MakeBuilder(rig, start_ns)) {}

Status SceneDepthProbe::AddEvents(events::Camera camera, std::span<const events::Event> events) {
  return builder_.AddEvents(camera, events);
}

Expected<std::optional<SceneDepth>> SceneDepthProbe::Measure(TimeNs t_ns) {
  events::Observation obs;
  AAVIO_RETURN_IF_ERROR(builder_.Build(t_ns, &obs));
  // Images of VGA and up are matched at half size: the depths the choice turns on (metres to
  // tens of metres) keep pixels of disparity, and SGM costs an eighth.
  const double scale = rig_.width() >= kHalfSizeFromWidth ? 0.5 : 1.0;
  mapping::RectifiedStereo stereo = mapping::RectifiedStereo::FromRig(rig_);
  cv::Mat left = obs.ts_left, right = obs.ts_right;
  if (scale != 1.0) {
    stereo.width = static_cast<int>(stereo.width * scale);
    stereo.height = static_cast<int>(stereo.height * scale);
    stereo.f *= scale;
    stereo.cx_left *= scale;
    stereo.cx_right *= scale;
    stereo.cy *= scale;
    cv::resize(obs.ts_left, left, cv::Size(stereo.width, stereo.height), 0, 0, cv::INTER_AREA);
    cv::resize(obs.ts_right, right, cv::Size(stereo.width, stereo.height), 0, 0, cv::INTER_AREA);
  }
  std::vector<Eigen::Vector2f> positions;
  positions.reserve(obs.samples.size());
  for (const events::EdgeSample& s : obs.samples)
    positions.emplace_back(static_cast<float>(static_cast<double>(s.u) * scale),
                           static_cast<float>(static_cast<double>(s.v) * scale));
  // Every depth from kNearestM (or what half the image's width of disparity allows) to
  // infinity; any number of points is an answer here (the bootstrap's acceptance is the
  // odometry's).
  const double nearest_rho =
      std::min(1.0 / kNearestM, 0.5 * stereo.width / std::max(1e-9, stereo.fb()));
  Expected<std::vector<mapping::DepthPoint>> points =
      mapping::BootstrapWithSgm(left, right, positions, stereo,
                                mapping::DepthRefinementConfig{}.student_t_nu, {1e-4, nearest_rho});
  if (!points) return points.status();
  if (static_cast<int>(points->size()) < kMinPoints) return std::optional<SceneDepth>{};
  SceneDepth scene;
  scene.depths_m.reserve(points->size());
  for (const mapping::DepthPoint& p : *points)
    scene.depths_m.push_back(1.0 / p.rho);
  std::sort(scene.depths_m.begin(), scene.depths_m.end());
  scene.at_s = NsToSeconds(t_ns - start_ns_);
  return std::optional<SceneDepth>{std::move(scene)};
}

}  // namespace aavio::pipeline
