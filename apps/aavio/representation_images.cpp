#include "representation_images.hpp"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "aavio/common/format.hpp"
#include "aavio/events/adaptive_accumulation.hpp"

namespace aavio::cli {

cv::Mat GradientImage(const cv::Mat& gradient) {
  cv::Mat out;
  gradient.convertTo(out, CV_8UC1, 2.0, 128.0);  // ±64 levels per pixel span the range
  return out;
}

cv::Mat AaBlocksImage(const events::Observation& obs, int grid_cols, int grid_rows) {
  const cv::Mat& counts = obs.aa_counts_raw;
  cv::Mat stretched;
  counts.convertTo(stretched, CV_8UC1, 60.0);  // 1 event → 60, ≥ 4 events → white
  cv::Mat image;
  cv::cvtColor(stretched, image, cv::COLOR_GRAY2BGR);
  const events::BlockGrid grid(counts.cols, counts.rows, grid_cols, grid_rows);
  for (int b = 0; b < grid.size() && b < static_cast<int>(obs.aa_blocks.size()); ++b) {
    // The block's pixel extent: the first and last columns/rows that map to it.
    const int bc = b % grid_cols, br = b / grid_cols;
    int x0 = counts.cols, x1 = 0, y0 = counts.rows, y1 = 0;
    for (int x = 0; x < counts.cols; ++x) {
      if (grid.BlockOf(x, 0) % grid_cols == bc) x0 = std::min(x0, x), x1 = std::max(x1, x);
    }
    for (int y = 0; y < counts.rows; ++y) {
      if (grid.BlockOf(0, y) / grid_cols == br) y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    const events::AaBlock& block = obs.aa_blocks[b];
    const cv::Scalar colour = block.closed ? cv::Scalar(0, 200, 0) : cv::Scalar(0, 0, 220);
    cv::rectangle(image, cv::Point(x0, y0), cv::Point(x1, y1), colour, 1);
    const double scale = counts.cols >= 480 ? 0.4 : 0.3;
    cv::putText(image, StrFormat("%.1fms", NsToSeconds(block.span_ns) * 1e3),
                cv::Point(x0 + 2, y0 + 11), cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1,
                cv::LINE_AA);
  }
  return image;
}

cv::Mat SamplesImage(const cv::Mat& background, const std::vector<events::EdgeSample>& samples,
                     const cv::Scalar& colour) {
  cv::Mat dim, image;
  background.convertTo(dim, CV_8UC1, 0.5, 0.0);
  cv::cvtColor(dim, image, cv::COLOR_GRAY2BGR);
  for (const events::EdgeSample& s : samples) {
    const int u = static_cast<int>(s.u + 0.5f), v = static_cast<int>(s.v + 0.5f);
    if (u >= 0 && v >= 0 && u < image.cols && v < image.rows) {
      image.at<cv::Vec3b>(v, u) =
          cv::Vec3b(static_cast<std::uint8_t>(colour[0]), static_cast<std::uint8_t>(colour[1]),
                    static_cast<std::uint8_t>(colour[2]));
    }
  }
  return image;
}

Expected<std::vector<std::string>> WriteRepresentationImages(
    const events::Observation& obs, const std::vector<events::EdgeSample>& esvo_samples,
    int grid_cols, int grid_rows, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return IoError(dir + ": cannot create the folder (" + ec.message() + ")");
  const std::vector<std::pair<std::string, cv::Mat>> views = {
      {"ts_left.png", obs.ts_left},
      {"ts_right.png", obs.ts_right},
      {"negative_ts_left.png", obs.negative_ts_left},
      {"gradient_u.png", GradientImage(obs.grad_u)},
      {"gradient_v.png", GradientImage(obs.grad_v)},
      {"aa_map.png", obs.aa_map},
      {"aa_blocks_raw.png", AaBlocksImage(obs, grid_cols, grid_rows)},
      {"samples.png", SamplesImage(obs.ts_left, obs.samples, cv::Scalar(0, 0, 255))},
      {"samples_esvo.png", SamplesImage(obs.ts_left, esvo_samples, cv::Scalar(255, 120, 0))},
  };
  std::vector<std::string> written;
  for (const auto& [name, image] : views) {
    const std::string path = (fs::path(dir) / name).string();
    if (!cv::imwrite(path, image)) return IoError(path + ": cannot write the image");
    written.push_back(name);
  }
  return written;
}

}  // namespace aavio::cli
