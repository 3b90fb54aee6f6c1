#include "aavio/recording/ply.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/test_utils.hpp"

namespace aavio::recording {
namespace {

TEST(Ply, RoundTripsPointsColoursAndComment) {
  const std::string path = (testing::ScratchDir() / "map.ply").string();
  const std::vector<Eigen::Vector3f> points = {
      {1.f, -2.f, 3.5f}, {0.f, 0.f, 0.f}, {1e3f, 2e-3f, -7.f}};
  const std::vector<Rgb> colours = {{255, 0, 0}, {0, 128, 255}, {1, 2, 3}};
  ASSERT_TRUE(WritePly(path, points, colours, "aavio test\nsecond line").ok());
  Expected<ColouredCloud> cloud = ReadPly(path);
  ASSERT_TRUE(cloud.ok()) << cloud.status().message();
  EXPECT_EQ(cloud->points, points);
  EXPECT_EQ(cloud->colours, colours);
  EXPECT_EQ(cloud->comment, "aavio test\nsecond line");
  // An empty cloud is a valid file too.
  ASSERT_TRUE(WritePly(path, {}, {}).ok());
  ASSERT_TRUE(ReadPly(path).ok());
  EXPECT_TRUE(ReadPly(path)->points.empty());
}

TEST(Ply, WriterStreamsBatchesIntoTheSameFile) {
  const auto dir = testing::ScratchDir();
  const std::vector<Eigen::Vector3f> points = {{1.f, 2.f, 3.f}, {4.f, 5.f, 6.f}, {7.f, 8.f, 9.f}};
  const std::vector<Rgb> colours = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  const std::string path = (dir / "streamed.ply").string();
  Expected<PlyWriter> writer = PlyWriter::Open(path, "streamed");
  ASSERT_TRUE(writer.ok()) << writer.status().message();
  ASSERT_TRUE(writer->Append(std::span(points).first(2), std::span(colours).first(2)).ok());
  ASSERT_TRUE(writer->Append({}, {}).ok());
  ASSERT_TRUE(writer->Append(std::span(points).last(1), std::span(colours).last(1)).ok());
  EXPECT_EQ(writer->size(), 3u);
  // Until it is closed only the part file exists.
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_TRUE(std::filesystem::exists(path + ".part"));
  ASSERT_TRUE(writer->Close().ok());
  EXPECT_FALSE(std::filesystem::exists(path + ".part"));
  // The whole cloud, as WritePly would write it (the header's count is padded by a blank comment).
  Expected<ColouredCloud> read = ReadPly(path);
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_EQ(read->points, points);
  EXPECT_EQ(read->colours, colours);
  EXPECT_EQ(read->comment, "streamed");
  EXPECT_NE(testing::ReadAll(path).find("element vertex 3\ncomment" + std::string(19, ' ') + "\n"),
            std::string::npos);
  // Mismatched batches and a second Close are refused; an empty cloud is a valid file.
  Expected<PlyWriter> empty = PlyWriter::Open(path);
  ASSERT_TRUE(empty.ok());
  EXPECT_FALSE(empty->Append(points, std::span(colours).first(1)).ok());
  ASSERT_TRUE(empty->Close().ok());
  EXPECT_FALSE(empty->Close().ok());
  ASSERT_TRUE(ReadPly(path).ok());
  EXPECT_TRUE(ReadPly(path)->points.empty());
  // A folder that cannot take the part file: an error naming it.
  Expected<PlyWriter> nowhere = PlyWriter::Open((dir / "missing" / "map.ply").string());
  ASSERT_FALSE(nowhere.ok());
  EXPECT_NE(nowhere.status().message().find("map.ply.part: cannot write"), std::string::npos);
}

TEST(Ply, WriterStoppedByAFullDiskLeavesTheVerticesWritten) {
  // A file size limit fails writes past it as a full disk does (EFBIG for ENOSPC).
  const std::string path = (testing::ScratchDir() / "cut.ply").string();
  std::vector<Eigen::Vector3f> points;
  std::vector<Rgb> colours;
  for (int i = 0; i < 100; ++i) {
    points.emplace_back(static_cast<float>(i), 1.f, 2.f);
    colours.push_back({static_cast<std::uint8_t>(i), 0, 0});
  }
  Expected<PlyWriter> writer = PlyWriter::Open(path, "cut");
  ASSERT_TRUE(writer.ok());
  rlimit limit{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &limit), 0);
  const rlimit saved = limit;
  auto* const previous = std::signal(SIGXFSZ, SIG_IGN);
  limit.rlim_cur = 600;  // the header (about 230 bytes) and some 24 vertices
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  ASSERT_TRUE(writer->Append(points, colours).ok());  // buffered: fails when flushed
  const Status closed = writer->Close();
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &saved), 0);
  std::signal(SIGXFSZ, previous);
  ASSERT_FALSE(closed.ok());
  EXPECT_NE(closed.message().find("of 100 points written"), std::string::npos) << closed.message();
  Expected<ColouredCloud> cloud = ReadPly(path);
  ASSERT_TRUE(cloud.ok()) << cloud.status().message();
  ASSERT_GT(cloud->points.size(), 10u);
  ASSERT_LT(cloud->points.size(), 100u);
  for (std::size_t i = 0; i < cloud->points.size(); ++i) {
    EXPECT_EQ(cloud->points[i], points[i]);
    EXPECT_EQ(cloud->colours[i], colours[i]);
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".part"));
}

TEST(Ply, RefusesBadFilesWithWhatIsWrong) {
  const auto dir = testing::ScratchDir();
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex %VERTICES%\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nend_header\n";
  auto with = [&](const std::string& vertices, std::size_t body_bytes) {
    std::string h = header;
    h.replace(h.find("%VERTICES%"), 10, vertices);
    return h + std::string(body_bytes, '\0');
  };
  struct Case {
    std::string text, expected;
  };
  const std::vector<Case> cases = {
      {"", "not a PLY file"},
      {"ply\nformat ascii 1.0\n", "only binary_little_endian 1.0 is read"},
      {testing::Replace(with("1", 15), "property float y", "property double y"),
       "expected float x y z and uchar red green blue"},
      {with("2", 15), "declares 2 vertices but the file holds 1"},
      // A corrupt count must not be allocated for.
      {with("999999999999", 30), "declares 999999999999 vertices but the file holds 2"},
      {testing::Replace(with("1", 0), "end_header\n", ""), "the header never ends"},
      // Binary data where a header line should be is quoted readably.
      {testing::Replace(with("1", 15), "end_header\n", ""),
       "\"???????????????\": unexpected header line"},
      {testing::Replace(with("1", 15), "element vertex 1\n", ""), "lacks the vertex element"},
      {testing::Replace(with("1", 15), "element vertex 1", "element vertex -3"),
       "bad vertex count"},
      {testing::Replace(with("1", 15), "end_header", "obj_info x\nend_header"),
       "unexpected header line"},
  };
  for (const Case& c : cases) {
    const auto path = dir / "bad.ply";
    testing::WriteFile(path, c.text);
    Expected<ColouredCloud> cloud = ReadPly(path.string());
    ASSERT_FALSE(cloud.ok()) << c.expected;
    EXPECT_NE(cloud.status().message().find(c.expected), std::string::npos)
        << "expected: " << c.expected << "\n got: " << cloud.status().message();
    EXPECT_NE(cloud.status().message().find("bad.ply"), std::string::npos);
  }
  EXPECT_FALSE(ReadPly((dir / "missing.ply").string()).ok());
  EXPECT_FALSE(
      WritePly((dir / "x.ply").string(), std::vector<Eigen::Vector3f>(2), std::vector<Rgb>(1))
          .ok());
}

}  // namespace
}  // namespace aavio::recording
