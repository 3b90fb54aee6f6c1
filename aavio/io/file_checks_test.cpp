#include "aavio/io/file_checks.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

namespace aavio::io {
namespace {

namespace fs = std::filesystem;

class FileChecks : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest runs them in parallel.
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("file_checks_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& contents) const {
    std::ofstream(Path(name), std::ios::binary) << contents;
    return Path(name);
  }
  fs::path dir_;
};

TEST_F(FileChecks, EachKindOfNonFileIsNamed) {
  fs::create_symlink("loop_b", Path("loop_a"));
  fs::create_symlink("loop_a", Path("loop_b"));
  fs::create_symlink("nothing", Path("dangling"));
  ASSERT_EQ(mkfifo(Path("fifo").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", Path("zero"));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {Path("missing"), "no such file (the calibration file)"},
      {Path("loop_a"), "a symbolic link that leads to no file"},
      {Path("dangling"), "a symbolic link that leads to no file"},
      {dir_.string(), "is a folder, not a file; give the calibration file itself"},
      {Path("fifo"), "is a named pipe (FIFO)"},
      {Path("zero"), "is a device, not a file"},
      {"", "an empty path was given as the calibration file"},
  };
  for (const auto& [path, fragment] : cases) {
    const Status status = CheckRegularFile(path, "calibration file");
    EXPECT_NE(status.message().find(fragment), std::string::npos)
        << path << ": " << status.message();
  }
  EXPECT_TRUE(CheckRegularFile(Write("ok.yaml", "a: 1\n"), "calibration file").ok());
}

TEST_F(FileChecks, ReadingIsBoundedAndRefusesBinaryWhereTextBelongs) {
  const std::string text = Write("t.txt", "0 1 2\n");
  EXPECT_EQ(*ReadBoundedFile(text, 6, "trajectory file"), "0 1 2\n");
  const Expected<std::string> large = ReadBoundedFile(text, 5, "trajectory file");
  ASSERT_FALSE(large.ok());
  EXPECT_NE(large.status().message().find("larger than the 0.0 MB a trajectory file may have"),
            std::string::npos)
      << large.status().message();
  const std::string binary = Write("b.yaml", std::string("a: \0\x01", 5));
  const Expected<std::string> refused = ReadBoundedFile(binary, 100, "YAML file");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("binary data (a NUL byte at byte 3)"),
            std::string::npos);
  EXPECT_EQ(ReadBoundedFile(binary, 100, "image", /*text=*/false)->size(), 5u);
  // A device is refused before a byte is read, whatever its size.
  EXPECT_NE(ReadBoundedFile("/dev/zero", 100, "YAML file").status().message().find("is a device"),
            std::string::npos);
}

TEST(PrintableExcerpt, CutsAndMasksWhatATerminalCannotShow) {
  EXPECT_EQ(PrintableExcerpt("abc", 80), "abc");
  EXPECT_EQ(PrintableExcerpt("abcdef", 3), "abc...");
  EXPECT_EQ(PrintableExcerpt(std::string("a\x1b[2Jb\xff", 7), 80), "a?[2Jb?");
}

}  // namespace
}  // namespace aavio::io
