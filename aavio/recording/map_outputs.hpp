#pragma once
/// The maps a run leaves: every confirmed local map into the global cloud, streamed to map.ply
/// (nothing of it kept in memory but its recent voxels), and five a second into `depth/` as a
/// DSEC-format disparity image with a colour picture of it over the time surface.

#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/events/observation.hpp"
#include "aavio/io/depth_folder_writer.hpp"
#include "aavio/mapping/global_cloud.hpp"
#include "aavio/mapping/local_map.hpp"
#include "aavio/mapping/mapping_config.hpp"
#include "aavio/recording/depth_images.hpp"
#include "aavio/recording/ply.hpp"

namespace aavio::recording {

class MapOutputs {
 public:
  /// Creates `depth_dir` and the cloud's file at `cloud_path`.
  static Expected<MapOutputs> Open(const std::string& depth_dir, const std::string& cloud_path,
                                   const mapping::RectifiedStereo& stereo,
                                   const mapping::MappingConfig& config);

  /// A confirmed map (drawn over the time surface of `observation`, which may be null): into the
  /// cloud, and every depth_every-th into depth/ — then its disparity image is returned (for
  /// scoring as `aavio eval --run` scores the file).
  Expected<std::optional<cv::Mat>> Add(const mapping::LocalMap& map,
                                       const events::Observation* observation);

  /// Ends map.ply (its points turned by `R_out_world`, if given) and depth/.
  Status CloseCloud(const std::optional<Eigen::Matrix3d>& R_out_world) {
    return cloud_file_.Close(R_out_world);
  }
  Status FinishDepth() { return depth_writer_.Finish(); }
  int depth_maps_written() const { return depth_writer_.count(); }

  /// Its keys of summary.json.
  void AddTo(nlohmann::json* summary) const;

 private:
  MapOutputs(io::DepthFolderWriter depth_writer, PlyWriter cloud_file,
             const mapping::RectifiedStereo& stereo, const mapping::MappingConfig& config);

  mapping::RectifiedStereo stereo_;
  io::DepthFolderWriter depth_writer_;
  int depth_every_;
  double cloud_depth_m_;
  mapping::GlobalCloud cloud_;
  PlyWriter cloud_file_;
  InverseDepthColours colours_;
  int confirmed_maps_ = 0;
  std::size_t confirmed_points_ = 0;
};

}  // namespace aavio::recording
