#pragma once
/// Writes a folder of depth maps in the layout ground_truth_depth.hpp reads (a sequence's
/// ground-truth depth and a run's `depth/` share it): per map `disparity_INDEX.png` (16-bit,
/// disparity × 256, 0 = none: DSEC's format; 1/256 px steps, 0.06 % of depth at 50 m on DSEC, and
/// a sparse map compresses to a few kB where a float TIFF takes 1.2 MB), optionally a colour
/// picture `inverse_depth_INDEX.png` beside it, and `timestamps.txt` ("t[s] index" lines).

#include <opencv2/core/mat.hpp>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"

namespace aavio::io {

class DepthFolderWriter {
 public:
  /// Creates `dir`, first removing it with the maps of an earlier run.
  static Expected<DepthFolderWriter> Create(const std::string& dir);

  /// Writes map number count() (INDEX = %06d of it): `disparity` CV_16UC1 (disparity × 256) and,
  /// if not empty, `picture` (8-bit BGR). Returns INDEX.
  Expected<std::string> Add(TimeNs t_ns, const cv::Mat& disparity, const cv::Mat& picture);
  /// Writes timestamps.txt; a folder that got no map is removed.
  Status Finish();

  const std::string& dir() const { return dir_; }
  int count() const { return count_; }

 private:
  explicit DepthFolderWriter(std::string dir) : dir_(std::move(dir)) {}
  std::string dir_;
  std::string stamps_ = "# t[s] index\n";
  int count_ = 0;
};

}  // namespace aavio::io
