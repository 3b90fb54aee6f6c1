#include "aavio/recording/map_outputs.hpp"

#include <algorithm>
#include <cmath>

namespace aavio::recording {

Expected<MapOutputs> MapOutputs::Open(const std::string& depth_dir, const std::string& cloud_path,
                                      const mapping::RectifiedStereo& stereo,
                                      const mapping::MappingConfig& config) {
  Expected<io::DepthFolderWriter> depth = io::DepthFolderWriter::Create(depth_dir);
  if (!depth) return depth.status();
  Expected<PlyWriter> cloud = PlyWriter::Open(cloud_path, "aavio global map (world frame, metres)");
  if (!cloud) return cloud.status();
  return MapOutputs(std::move(*depth), std::move(*cloud), stereo, config);
}

MapOutputs::MapOutputs(io::DepthFolderWriter depth_writer, PlyWriter cloud_file,
                       const mapping::RectifiedStereo& stereo, const mapping::MappingConfig& config)
    : stereo_(stereo),
      depth_writer_(std::move(depth_writer)),
      // Every `depth_every_` confirmed maps (5 per second at the presets' 20 Hz) one goes to
      // depth/.
      depth_every_(std::max(1, static_cast<int>(std::lround(config.rate_hz / 5.0)))),
      // map.ply: points up to the far end of the depth range (at most 50 m) on voxels of 0.5 % of
      // it (rpg 0.5–5 m: 2.5 cm; DSEC: 25 cm).
      cloud_depth_m_(std::min(1.0 / config.inv_depth_min, 50.0)),
      cloud_(0.005 * cloud_depth_m_),
      cloud_file_(std::move(cloud_file)),
      colours_(config.inv_depth_min, config.inv_depth_max) {}

Expected<std::optional<cv::Mat>> MapOutputs::Add(const mapping::LocalMap& map,
                                                 const events::Observation* observation) {
  std::vector<mapping::CloudPoint> added;
  cloud_.Add(map, cloud_depth_m_, &added);
  std::vector<Eigen::Vector3f> points;
  std::vector<Rgb> rgb;
  for (const mapping::CloudPoint& p : added) {
    const cv::Vec3b c = colours_(static_cast<double>(p.inv_depth));
    points.push_back(p.p_world);
    rgb.push_back({c[2], c[1], c[0]});
  }
  AAVIO_RETURN_IF_ERROR(cloud_file_.Append(points, rgb));
  ++confirmed_maps_;
  confirmed_points_ += map.points.size();
  if ((confirmed_maps_ - 1) % depth_every_ != 0) return std::optional<cv::Mat>();
  cv::Mat disparity = DisparityImage(map, stereo_);
  Expected<std::string> index =
      depth_writer_.Add(map.t_ns, disparity,
                        InverseDepthPicture(map, stereo_.width, stereo_.height, colours_,
                                            observation ? observation->ts_left : cv::Mat()));
  if (!index) return index.status();
  return std::optional<cv::Mat>(std::move(disparity));
}

void MapOutputs::AddTo(nlohmann::json* summary) const {
  nlohmann::json& s = *summary;
  s["depth_maps"] = confirmed_maps_;
  s["depth_maps_written"] = depth_writer_.count();
  s["mean_map_points"] =
      confirmed_maps_ > 0 ? static_cast<double>(confirmed_points_) / confirmed_maps_ : 0.0;
  s["map_points_global"] = cloud_.size();
}

}  // namespace aavio::recording
