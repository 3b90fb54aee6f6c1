#pragma once
/// The output folder of a command (a run, a simulated or converted sequence): never mixed with an
/// earlier run's files, never overwritten without being asked, and checked before any work starts.

#include <cstdint>
#include <span>
#include <string>

#include "aavio/common/status.hpp"

namespace aavio::io {

struct OutputFolderOptions {
  /// Files or folders directly in the folder that the command writes.
  std::span<const char* const> outputs;
  /// Remove earlier outputs instead of refusing the folder (the command's --overwrite).
  bool overwrite = false;
  /// The command's option that names the folder, for messages.
  std::string option = "--out";
  /// Refuse to start with less free space than this (a full disk).
  std::uint64_t min_free_bytes = 64ull << 20;
};

/// Creates `dir` if needed. When it holds any of `options.outputs`: an error naming them and the
/// fix, or with `overwrite` they are removed (nothing else in the folder is touched). Then the
/// folder must take a file (a probe, removed again) and have `min_free_bytes` free; otherwise an
/// error naming the folder and the cause.
Status PrepareOutputFolder(const std::string& dir, const OutputFolderOptions& options);

/// "<path>: cannot write (the disk is full)", or with the system's reason: for a write that failed
/// without saying why (an image encoder's).
std::string CannotWrite(const std::string& path);

/// Disk space held back in a file of its own so that a command stopped by a full disk can still
/// write what it has done (a run's trajectory and summary): Release() frees it for those last
/// files. Released on destruction as well.
class DiskReserve {
 public:
  /// Allocates `bytes` to the file `path` (posix_fallocate: the blocks are taken, not just
  /// promised). An error naming the file when the disk cannot give them.
  static Expected<DiskReserve> Create(const std::string& path, std::uint64_t bytes);
  DiskReserve(DiskReserve&& other) noexcept : path_(std::move(other.path_)) { other.path_.clear(); }
  DiskReserve& operator=(DiskReserve&& other) noexcept;
  DiskReserve(const DiskReserve&) = delete;
  DiskReserve& operator=(const DiskReserve&) = delete;
  ~DiskReserve() { Release(); }

  /// Removes the file (once; later calls do nothing).
  void Release();

 private:
  explicit DiskReserve(std::string path) : path_(std::move(path)) {}
  std::string path_;
};

}  // namespace aavio::io
