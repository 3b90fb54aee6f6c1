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

// The images are written on the writer's thread: Add copies them (a caller may reuse its
// images at once), and a write that fails comes back from the next Add or from Finish, naming
// the file.
TEST(DepthFolderWriter, WritesCopiesInTheBackgroundAndReportsAFailedWriteLater) {
  const fs::path dir = testing::ScratchDir() / "depth";
  Expected<DepthFolderWriter> writer = DepthFolderWriter::Create(dir.string());
  ASSERT_TRUE(writer.ok()) << writer.status().message();
  cv::Mat disparity(4, 6, CV_16UC1, cv::Scalar(3 * 256));
  ASSERT_TRUE(writer->Add(1'000'000'000, disparity, cv::Mat()).ok());
  disparity.setTo(cv::Scalar(0));  // after Add: not what was written
  ASSERT_TRUE(writer->Finish().ok());
  EXPECT_EQ(writer->count(), 1);
  Expected<std::vector<GtDepthEntry>> index = ReadGtDepthIndex(dir.string());
  ASSERT_TRUE(index.ok()) << index.status().message();
  Expected<GtDepthFrame> frame = LoadGtDepthFrame(dir.string(), (*index)[0], 30.0, 0.0);
  ASSERT_TRUE(frame.ok()) << frame.status().message();
  EXPECT_FLOAT_EQ(frame->depth_m.at<float>(2, 3), 10.0f);

  const fs::path gone = testing::ScratchDir() / "gone";
  Expected<DepthFolderWriter> lost = DepthFolderWriter::Create(gone.string());
  ASSERT_TRUE(lost.ok());
  fs::remove_all(gone);  // every write into it fails
  const cv::Mat picture(4, 6, CV_8UC3, cv::Scalar(0, 0, 255));
  Status status = Status::Ok();
  for (int i = 0; i < 5 && status.ok(); ++i) {
    Expected<std::string> added = lost->Add(i * 200'000'000, disparity, picture);
    if (!added) status = added.status();
  }
  if (status.ok()) status = lost->Finish();
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("gone/disparity_000000.png: cannot write"), std::string::npos)
      << status.message();
  EXPECT_EQ(lost->count(), 0);
  EXPECT_FALSE(lost->Finish().ok());
}

}  // namespace
}  // namespace aavio::io
