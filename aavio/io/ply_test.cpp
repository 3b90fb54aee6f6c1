#include "aavio/io/ply.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/test_utils.hpp"

namespace aavio::io {
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
}  // namespace aavio::io
