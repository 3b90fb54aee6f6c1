#include "aavio/io/ground_truth_depth.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

TEST(GroundTruthDepth, ReadsTiffDisparityAndEdges) {
  const auto dir = testing::ScratchDir();
  testing::WriteFile(dir / "timestamps.txt", "# t[s] index\n10.000 000000\n10.050 000001\n");
  cv::Mat depth(4, 6, CV_32FC1, cv::Scalar(12.5f));
  ASSERT_TRUE(cv::imwrite((dir / "depth_000000.tiff").string(), depth));
  cv::Mat disparity(4, 6, CV_16UC1, cv::Scalar(20 * 256));  // 20 px
  disparity.at<std::uint16_t>(0, 0) = 0;                    // no ground truth
  ASSERT_TRUE(cv::imwrite((dir / "disparity_000001.png").string(), disparity));
  cv::Mat edges(4, 6, CV_8UC1, cv::Scalar(0));
  edges.row(2).setTo(255);
  ASSERT_TRUE(cv::imwrite((dir / "edges_000000.png").string(), edges));

  const Expected<std::vector<GtDepthEntry>> index = ReadGtDepthIndex(dir.string());
  ASSERT_TRUE(index.ok()) << index.status().message();
  ASSERT_EQ(index->size(), 2u);
  EXPECT_EQ((*index)[1].t_ns, 10'050'000'000LL);
  const Expected<GtDepthFrame> a = LoadGtDepthFrame(dir.string(), (*index)[0]);
  ASSERT_TRUE(a.ok()) << a.status().message();
  EXPECT_FLOAT_EQ(a->depth_m.at<float>(1, 1), 12.5f);
  EXPECT_EQ(a->edges.at<std::uint8_t>(2, 3), 255);
  // Disparity PNGs need f·b; depth = f·b / (d − offset).
  EXPECT_FALSE(LoadGtDepthFrame(dir.string(), (*index)[1]).ok());
  const Expected<GtDepthFrame> b = LoadGtDepthFrame(dir.string(), (*index)[1], 100.0, 0.0);
  ASSERT_TRUE(b.ok());
  EXPECT_FLOAT_EQ(b->depth_m.at<float>(1, 1), 5.0f);
  EXPECT_FLOAT_EQ(b->depth_m.at<float>(0, 0), 0.0f);
  EXPECT_TRUE(b->edges.empty());
}

TEST(GroundTruthDepth, ClearErrors) {
  const auto dir = testing::ScratchDir();
  EXPECT_NE(ReadGtDepthIndex(dir.string()).status().message().find("timestamps.txt"),
            std::string::npos);
  testing::WriteFile(dir / "timestamps.txt", "10.0 000000\n9.0 000001\n");
  EXPECT_NE(ReadGtDepthIndex(dir.string())
                .status()
                .message()
                .find("timestamps.txt:2: time stamps must increase"),
            std::string::npos);
  testing::WriteFile(dir / "timestamps.txt", "10.0\n");
  EXPECT_NE(ReadGtDepthIndex(dir.string()).status().message().find("timestamps.txt:1: expected"),
            std::string::npos);
  testing::WriteFile(dir / "timestamps.txt", "ten 000000\n");
  EXPECT_FALSE(ReadGtDepthIndex(dir.string()).ok());
  const Status missing = LoadGtDepthFrame(dir.string(), {0, "000007"}).status();
  EXPECT_NE(missing.message().find("neither depth_000007.tiff nor disparity_000007.png"),
            std::string::npos)
      << missing.message();
  ASSERT_TRUE(cv::imwrite((dir / "depth_000008.tiff").string(), cv::Mat(3, 3, CV_8UC1)));
  EXPECT_NE(LoadGtDepthFrame(dir.string(), {0, "000008"}).status().message().find("32-bit float"),
            std::string::npos);
}

}  // namespace
}  // namespace aavio::io
