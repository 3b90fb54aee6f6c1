#include "aavio/io/depth_folder_writer.hpp"

#include <cerrno>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/output_folder.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

namespace {
// A failed image: an error saying why, and no partial file left.
Status Failed(const std::string& png) {
  Status failed = IoError(CannotWrite(png));
  std::error_code ec;
  fs::remove(png, ec);
  return failed;
}
}  // namespace

Expected<DepthFolderWriter> DepthFolderWriter::Create(const std::string& dir) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (ec) return IoError(dir + ": cannot remove the earlier maps (" + ec.message() + ")");
  fs::create_directories(dir, ec);
  if (ec) return IoError(dir + ": cannot create the folder (" + ec.message() + ")");
  return DepthFolderWriter(dir);
}

Expected<std::string> DepthFolderWriter::Add(TimeNs t_ns, const cv::Mat& disparity,
                                             const cv::Mat& picture) {
  if (disparity.type() != CV_16UC1)
    return InvalidArgument("DepthFolderWriter: the disparity image must be CV_16UC1");
  const std::string index = StrFormat("%06d", count_);
  const std::string disparity_png = (fs::path(dir_) / ("disparity_" + index + ".png")).string();
  errno = 0;  // so that a failure's reason is the encoder's
  if (!cv::imwrite(disparity_png, disparity)) return Failed(disparity_png);
  if (!picture.empty()) {
    const std::string picture_png = (fs::path(dir_) / ("inverse_depth_" + index + ".png")).string();
    if (!cv::imwrite(picture_png, picture)) {
      const Status failed = Failed(picture_png);
      std::error_code ec;
      fs::remove(disparity_png, ec);  // the index lists pairs written whole
      return failed;
    }
  }
  stamps_ += StrFormat("%.9f %s\n", NsToSeconds(t_ns), index.c_str());
  ++count_;
  return index;
}

Status DepthFolderWriter::Finish() {
  if (count_ == 0) {  // no map: no folder, rather than an index that lists nothing
    std::error_code ec;
    fs::remove_all(dir_, ec);
    return Status::Ok();
  }
  return WriteTextFile((fs::path(dir_) / "timestamps.txt").string(), stamps_);
}

}  // namespace aavio::io
