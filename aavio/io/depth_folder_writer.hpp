#pragma once
/// Writes a folder of depth maps in the layout ground_truth_depth.hpp reads (a sequence's
/// ground-truth depth and a run's `depth/` share it): per map `disparity_INDEX.png` (16-bit,
/// disparity × 256, 0 = none: DSEC's format; 1/256 px steps, 0.06 % of depth at 50 m on DSEC, and
/// a sparse map compresses to a few kB where a float TIFF takes 1.2 MB), optionally a colour
/// picture `inverse_depth_INDEX.png` beside it, and `timestamps.txt` ("t[s] index" lines).
///
/// The images are encoded and written on a thread of the writer's own, in the order they were
/// added, at most two maps behind: compressing them (several ms a map at VGA) stays off the
/// caller's thread. A write's failure comes back from the next Add, or from Finish.

#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"

namespace aavio::io {

class DepthFolderWriter {
 public:
  /// Creates `dir`, first removing it with the maps of an earlier run.
  static Expected<DepthFolderWriter> Create(const std::string& dir);
  DepthFolderWriter(DepthFolderWriter&&) noexcept;
  DepthFolderWriter& operator=(DepthFolderWriter&&) noexcept;
  ~DepthFolderWriter();  ///< waits for the maps still being written

  /// Queues map number INDEX (%06d of the maps added so far): `disparity` CV_16UC1 (disparity ×
  /// 256) and, if not empty, `picture` (8-bit BGR), both copied. Returns INDEX, or the error of
  /// an earlier map's write (after which nothing more is written).
  Expected<std::string> Add(TimeNs t_ns, const cv::Mat& disparity, const cv::Mat& picture);
  /// Waits for every queued map, then writes timestamps.txt listing the maps written whole; a
  /// folder that got no map is removed. Returns the first failure.
  Status Finish();

  const std::string& dir() const { return dir_; }
  /// Maps written whole so far (all of them once Finish returned).
  int count() const;

 private:
  struct Queue;
  explicit DepthFolderWriter(std::string dir);
  std::string dir_;
  int added_ = 0;
  std::unique_ptr<Queue> queue_;
};

}  // namespace aavio::io
