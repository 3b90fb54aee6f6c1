#include "aavio/io/depth_folder_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "aavio/io/ground_truth_depth.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

namespace fs = std::filesystem;

// What the writer writes, the ground-truth reader reads back: disparities exactly, as depth.
TEST(DepthFolderWriter, WritesWhatTheDepthReaderReads) {
  const fs::path dir = testing::ScratchDir() / "depth";
  fs::create_directories(dir);
  testing::WriteFile(dir / "disparity_000007.png", "an earlier run's");
  Expected<DepthFolderWriter> writer = DepthFolderWriter::Create(dir.string());
  ASSERT_TRUE(writer.ok()) << writer.status().message();
  EXPECT_FALSE(fs::exists(dir / "disparity_000007.png"));
  cv::Mat disparity(4, 6, CV_16UC1, cv::Scalar(0));
  disparity.at<std::uint16_t>(1, 2) = 10 * 256;       // 10 px
  disparity.at<std::uint16_t>(3, 5) = 2 * 256 + 128;  // 2.5 px
  const cv::Mat picture(4, 6, CV_8UC3, cv::Scalar(0, 0, 255));
  Expected<std::string> first = writer->Add(1'500'000'000, disparity, picture);
  Expected<std::string> second = writer->Add(1'700'000'000, disparity, cv::Mat());
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_EQ(*first, "000000");
  EXPECT_EQ(*second, "000001");
  ASSERT_TRUE(writer->Finish().ok());
  EXPECT_TRUE(fs::exists(dir / "inverse_depth_000000.png"));
  EXPECT_FALSE(fs::exists(dir / "inverse_depth_000001.png"));

  Expected<std::vector<GtDepthEntry>> index = ReadGtDepthIndex(dir.string());
  ASSERT_TRUE(index.ok()) << index.status().message();
  ASSERT_EQ(index->size(), 2u);
  EXPECT_EQ((*index)[1].t_ns, 1'700'000'000);
  // f·b = 20 px·m, principal-point offset 0.5 px: depth = 20 / (d − 0.5).
  Expected<GtDepthFrame> frame = LoadGtDepthFrame(dir.string(), (*index)[0], 20.0, 0.5);
  ASSERT_TRUE(frame.ok()) << frame.status().message();
  EXPECT_FLOAT_EQ(frame->depth_m.at<float>(1, 2), 20.0f / 9.5f);
  EXPECT_FLOAT_EQ(frame->depth_m.at<float>(3, 5), 10.0f);
  EXPECT_EQ(frame->depth_m.at<float>(0, 0), 0.0f);
  EXPECT_EQ(cv::countNonZero(DepthFromDisparityImage(disparity, 20.0, 0.5)), 2);
}

TEST(DepthFolderWriter, AFolderWithoutMapsIsRemovedAndBadImagesAreRefused) {
  const fs::path dir = testing::ScratchDir() / "depth";
  Expected<DepthFolderWriter> writer = DepthFolderWriter::Create(dir.string());
  ASSERT_TRUE(writer.ok());
  EXPECT_FALSE(writer->Add(0, cv::Mat(4, 6, CV_32FC1, cv::Scalar(1)), cv::Mat()).ok());
  ASSERT_TRUE(writer->Finish().ok());
  EXPECT_FALSE(fs::exists(dir));  // rather than an index that lists nothing
  // A folder that cannot be made says so.
  const fs::path file = testing::ScratchDir() / "a_file";
  testing::WriteFile(file, "x");
  Expected<DepthFolderWriter> under_file = DepthFolderWriter::Create((file / "depth").string());
  ASSERT_FALSE(under_file.ok());
  EXPECT_NE(under_file.status().message().find("a_file/depth"), std::string::npos)
      << under_file.status().message();
}

}  // namespace
}  // namespace aavio::io
