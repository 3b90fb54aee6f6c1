#include "aavio/io/ground_truth_depth.hpp"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "aavio/common/format.hpp"
#include "aavio/io/file_checks.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

namespace {
constexpr char kUndecodable[] =
    ": cannot be decoded as an image (corrupt or truncated?); re-extract the ground truth";
}  // namespace

Expected<std::vector<GtDepthEntry>> ReadGtDepthIndex(const std::string& dir) {
  const std::string path = (fs::path(dir) / "timestamps.txt").string();
  Expected<std::string> text =
      ReadBoundedFile(path, kMaxSettingsFileBytes, "ground-truth depth index (timestamps.txt)");
  if (!text) return text.status();
  std::istringstream in(*text);
  std::vector<GtDepthEntry> entries;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string t, index;
    if (!(fields >> t >> index)) {
      return ParseError(StrFormat("%s:%d: expected \"t[s] index\", got \"%s\"", path.c_str(),
                                  number, PrintableExcerpt(line).c_str()));
    }
    Expected<TimeNs> t_ns = ParseSecondsToNs(t);
    if (!t_ns) return t_ns.status().WithContext(StrFormat("%s:%d", path.c_str(), number));
    if (!entries.empty() && *t_ns <= entries.back().t_ns) {
      return ParseError(StrFormat("%s:%d: time stamps must increase", path.c_str(), number));
    }
    entries.push_back({*t_ns, index});
  }
  if (entries.empty()) return ParseError(path + ": lists no depth maps");
  return entries;
}

cv::Mat DepthFromDisparityImage(const cv::Mat& disparity, double fb, double disparity_offset) {
  cv::Mat depth_m(disparity.size(), CV_32FC1, cv::Scalar(0));
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) {
      const std::uint16_t raw = disparity.at<std::uint16_t>(y, x);
      const double d = raw / 256.0 - disparity_offset;
      if (raw != 0 && d > 0.0) depth_m.at<float>(y, x) = static_cast<float>(fb / d);
    }
  }
  return depth_m;
}

Expected<GtDepthFrame> LoadGtDepthFrame(const std::string& dir, const GtDepthEntry& entry,
                                        double fb, double disparity_offset) {
  GtDepthFrame frame;
  frame.t_ns = entry.t_ns;
  const fs::path tiff = fs::path(dir) / ("depth_" + entry.index + ".tiff");
  const fs::path png = fs::path(dir) / ("disparity_" + entry.index + ".png");
  if (fs::exists(tiff)) {
    AAVIO_RETURN_IF_ERROR(CheckRegularFile(tiff.string(), "ground-truth depth image"));
    frame.depth_m = cv::imread(tiff.string(), cv::IMREAD_UNCHANGED);
    if (frame.depth_m.empty()) return ParseError(tiff.string() + kUndecodable);
    if (frame.depth_m.type() != CV_32FC1) {
      return ParseError(tiff.string() + ": expected a single-channel 32-bit float image (metres)");
    }
  } else if (fs::exists(png)) {
    if (fb <= 0.0) return InvalidArgument(png.string() + ": disparity needs the rig's f·b");
    AAVIO_RETURN_IF_ERROR(CheckRegularFile(png.string(), "ground-truth disparity image"));
    const cv::Mat disparity = cv::imread(png.string(), cv::IMREAD_UNCHANGED);
    if (disparity.empty()) return ParseError(png.string() + kUndecodable);
    if (disparity.type() != CV_16UC1) {
      return ParseError(png.string() + ": expected a 16-bit single-channel PNG (disparity × 256)");
    }
    frame.depth_m = DepthFromDisparityImage(disparity, fb, disparity_offset);
  } else {
    return NotFound(StrFormat("%s: neither depth_%s.tiff nor disparity_%s.png exists", dir.c_str(),
                              entry.index.c_str(), entry.index.c_str()));
  }
  const fs::path edges = fs::path(dir) / ("edges_" + entry.index + ".png");
  if (fs::exists(edges)) {
    frame.edges = cv::imread(edges.string(), cv::IMREAD_UNCHANGED);
    if (frame.edges.type() != CV_8UC1 || frame.edges.size() != frame.depth_m.size()) {
      return ParseError(edges.string() + ": expected an 8-bit label image of the depth map's size");
    }
  }
  return frame;
}

}  // namespace aavio::io
