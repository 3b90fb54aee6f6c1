#include "aavio/io/output_folder.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>

#include "aavio/io/config_yaml.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

namespace fs = std::filesystem;
constexpr const char* kOutputs[] = {"summary.json", "depth"};

TEST(OutputFolder, CreatesAMissingFolderAndLeavesNoProbeBehind) {
  const fs::path dir = testing::ScratchDir() / "new" / "run";
  ASSERT_TRUE(PrepareOutputFolder(dir.string(), {.outputs = kOutputs}).ok());
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(OutputFolder, AnEarlierRunIsRefusedOrReplacedWithOverwriteOnly) {
  const fs::path dir = testing::ScratchDir();
  testing::WriteFile(dir / "summary.json", "{}");
  testing::WriteFile(dir / "depth" / "depth_000000.tiff", "x");
  testing::WriteFile(dir / "notes.txt", "the user's own file");
  Status refused = PrepareOutputFolder(dir.string(), {.outputs = kOutputs});
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find(dir.string() +
                                   ": holds the outputs of an earlier run (summary.json, depth); "
                                   "pass --overwrite to replace them, or give --out another "
                                   "folder"),
            std::string::npos)
      << refused.message();
  EXPECT_TRUE(fs::exists(dir / "summary.json"));  // refused: nothing touched

  ASSERT_TRUE(PrepareOutputFolder(dir.string(), {.outputs = kOutputs, .overwrite = true}).ok());
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  EXPECT_FALSE(fs::exists(dir / "depth"));
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));  // not ours: kept
  // Other files alone are no earlier run.
  EXPECT_TRUE(PrepareOutputFolder(dir.string(), {.outputs = kOutputs}).ok());
}

TEST(OutputFolder, AFileOrAnUnwritableFolderIsAClearError) {
  const fs::path dir = testing::ScratchDir();
  const std::string file = testing::WriteFile(dir / "a_file", "x");
  Status not_folder = PrepareOutputFolder(file, {.outputs = kOutputs, .option = "--out"});
  ASSERT_FALSE(not_folder.ok());
  EXPECT_NE(not_folder.message().find("a_file: is a file, not a folder"), std::string::npos)
      << not_folder.message();

  // Unwritable: /proc refuses new files even to root.
  Status unwritable = PrepareOutputFolder("/proc/self", {.outputs = kOutputs});
  ASSERT_FALSE(unwritable.ok());
  EXPECT_NE(unwritable.message().find("/proc/self: cannot write into the folder"),
            std::string::npos)
      << unwritable.message();
}

TEST(OutputFolder, TooLittleFreeSpaceIsRefusedBeforeTheRun) {
  const fs::path dir = testing::ScratchDir();
  Status full = PrepareOutputFolder(
      dir.string(), {.outputs = kOutputs, .option = "--out", .min_free_bytes = ~0ull >> 1});
  ASSERT_FALSE(full.ok());
  EXPECT_NE(full.message().find("MB free on its disk"), std::string::npos) << full.message();
}

TEST(OutputFolder, AWriteToAFullDiskIsAnErrorNotASilentLoss) {
  // /dev/full fails every write with ENOSPC, as a full disk does.
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  Status s = WriteTextFile("/dev/full", std::string(1 << 16, 'x'));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("/dev/full: write failed (disk full?)"), std::string::npos)
      << s.message();
}

TEST(DiskReserve, HoldsItsSpaceUntilReleased) {
  const fs::path dir = testing::ScratchDir();
  const std::string path = (dir / ".reserve").string();
  {
    Expected<DiskReserve> reserve = DiskReserve::Create(path, 1 << 20);
    ASSERT_TRUE(reserve.ok()) << reserve.status().message();
    ASSERT_TRUE(fs::exists(path));
    struct stat st {};
    ASSERT_EQ(::stat(path.c_str(), &st), 0);
    EXPECT_GE(static_cast<std::int64_t>(st.st_blocks) * 512, 1 << 20);  // allocated, not sparse
    DiskReserve moved = std::move(*reserve);
    moved.Release();
    EXPECT_FALSE(fs::exists(path));
    moved.Release();                                    // once only
    ASSERT_TRUE(DiskReserve::Create(path, 4096).ok());  // and on destruction
  }
  EXPECT_FALSE(fs::exists(path));
  Expected<DiskReserve> nowhere = DiskReserve::Create((dir / "missing" / "r").string(), 4096);
  ASSERT_FALSE(nowhere.ok());
  EXPECT_NE(nowhere.status().message().find("missing/r: cannot create"), std::string::npos)
      << nowhere.status().message();
  // More than the disk holds: an error, and no file left.
  Expected<DiskReserve> huge = DiskReserve::Create(path, ~0ull >> 2);
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.status().message().find("cannot set aside"), std::string::npos)
      << huge.status().message();
  EXPECT_FALSE(fs::exists(path));
}

TEST(OutputFolder, CannotWriteSaysWhenTheDiskIsFull) {
  errno = ENOSPC;
  EXPECT_EQ(CannotWrite("out/x.png"), "out/x.png: cannot write (the disk is full)");
  const std::string path = (testing::ScratchDir() / "x.png").string();
  errno = EACCES;
  EXPECT_EQ(CannotWrite(path), path + ": cannot write (Permission denied)");
}

}  // namespace
}  // namespace aavio::io
