#include "aavio/io/output_folder.hpp"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "aavio/common/format.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

Status PrepareOutputFolder(const std::string& dir, const OutputFolderOptions& options) {
  const fs::path folder(dir);
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec)) {
    return IoError(dir + ": is a file, not a folder; give " + options.option +
                   " a folder (it is created if missing)");
  }
  fs::create_directories(folder, ec);
  if (ec) return IoError(dir + ": cannot create the folder (" + ec.message() + ")");

  std::vector<std::string> earlier;
  for (const char* name : options.outputs) {
    if (fs::exists(folder / name, ec)) earlier.emplace_back(name);
  }
  if (!earlier.empty() && !options.overwrite) {
    std::string names;
    for (const std::string& n : earlier)
      names += (names.empty() ? "" : ", ") + n;
    return FailedPrecondition(dir + ": holds the outputs of an earlier run (" + names +
                              "); pass --overwrite to replace them, or give " + options.option +
                              " another folder");
  }
  for (const std::string& name : earlier) {
    fs::remove_all(folder / name, ec);
    if (ec) {
      return IoError((folder / name).string() + ": cannot remove an earlier run's output (" +
                     ec.message() + ")");
    }
  }

  // Writable? A probe file, written, flushed and removed.
  const fs::path probe = folder / ".aavio_write_probe";
  {
    std::ofstream out(probe, std::ios::binary | std::ios::trunc);
    out << "probe\n";
    out.flush();
    if (!out) {
      const std::string cause = std::strerror(errno);
      fs::remove(probe, ec);
      return IoError(dir + ": cannot write into the folder (" + cause + "); give " +
                     options.option + " a folder you can write to");
    }
  }
  fs::remove(probe, ec);
  struct statvfs st {};
  if (::statvfs(dir.c_str(), &st) == 0) {
    const std::uint64_t free_bytes =
        static_cast<std::uint64_t>(st.f_bavail) * static_cast<std::uint64_t>(st.f_frsize);
    if (free_bytes < options.min_free_bytes) {
      return IoError(StrFormat(
          "%s: only %.1f MB free on its disk (at least %.0f MB needed); free "
          "some space or give %s a folder on another disk",
          dir.c_str(), static_cast<double>(free_bytes) / 1048576.0,
          static_cast<double>(options.min_free_bytes) / 1048576.0, options.option.c_str()));
    }
  }
  return Status::Ok();
}

std::string CannotWrite(const std::string& path) {
  const int error = errno;
  struct statvfs st {};
  const std::string dir = fs::path(path).parent_path().string();
  if (error == ENOSPC || (::statvfs(dir.empty() ? "." : dir.c_str(), &st) == 0 && st.f_bavail == 0))
    return path + ": cannot write (the disk is full)";
  return path + ": cannot write" +
         (error != 0 ? " (" + std::string(std::strerror(error)) + ")" : "");
}

Expected<DiskReserve> DiskReserve::Create(const std::string& path, std::uint64_t bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return IoError(path + ": cannot create (" + std::strerror(errno) + ")");
  const int error = bytes > 0 ? ::posix_fallocate(fd, 0, static_cast<off_t>(bytes)) : 0;
  ::close(fd);
  if (error != 0) {
    std::error_code ec;
    fs::remove(path, ec);
    return IoError(StrFormat("%s: cannot set aside %.0f MB (%s); free some space", path.c_str(),
                             static_cast<double>(bytes) / 1048576.0, std::strerror(error)));
  }
  return DiskReserve(path);
}

DiskReserve& DiskReserve::operator=(DiskReserve&& other) noexcept {
  if (this != &other) {
    Release();
    path_ = std::move(other.path_);
    other.path_.clear();
  }
  return *this;
}

void DiskReserve::Release() {
  if (path_.empty()) return;
  std::error_code ec;
  fs::remove(path_, ec);
  path_.clear();
}

}  // namespace aavio::io
