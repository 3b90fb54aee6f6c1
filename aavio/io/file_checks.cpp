#include "aavio/io/file_checks.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "aavio/common/format.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

namespace {

std::string Megabytes(std::uint64_t bytes) {
  return StrFormat("%.1f MB", static_cast<double>(bytes) / (1 << 20));
}

}  // namespace

Status CheckRegularFile(const std::string& path, const std::string& role) {
  if (path.empty()) return InvalidArgument("an empty path was given as the " + role);
  std::error_code link_ec;
  const fs::file_status link = fs::symlink_status(path, link_ec);
  if (link.type() == fs::file_type::not_found || link.type() == fs::file_type::none) {
    return NotFound(path + ": no such file (the " + role + ")");
  }
  std::error_code ec;
  const fs::file_status target = fs::status(path, ec);
  if (fs::is_symlink(link) && (ec || target.type() == fs::file_type::not_found)) {
    return NotFound(path + ": a symbolic link that leads to no file (" + ec.message() +
                    "); point it at the " + role);
  }
  if (ec) return IoError(path + ": cannot inspect the " + role + ": " + ec.message());
  switch (target.type()) {
    case fs::file_type::regular:
      return Status::Ok();
    case fs::file_type::directory:
      return InvalidArgument(path + ": is a folder, not a file; give the " + role + " itself");
    case fs::file_type::fifo:
      return InvalidArgument(path + ": is a named pipe (FIFO), not a file; aavio reads the " +
                             role + " from a file on disk, so save the stream to one first");
    case fs::file_type::character:
    case fs::file_type::block:
      return InvalidArgument(path + ": is a device, not a file; give the " + role +
                             " as a file on disk");
    case fs::file_type::socket:
      return InvalidArgument(path + ": is a socket, not a file; give the " + role +
                             " as a file on disk");
    default:
      return InvalidArgument(path + ": is not a regular file; give the " + role +
                             " as a file on disk");
  }
}

Expected<std::string> ReadBoundedFile(const std::string& path, std::uint64_t max_bytes,
                                      const std::string& role, bool text) {
  AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, role));
  const std::string too_large = " is larger than the " + Megabytes(max_bytes) + " a " + role +
                                " may have; is this the right file?";
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes) {
    return InvalidArgument(path + ": " + Megabytes(size) + "," + too_large);
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
  if (!file) return IoError(path + ": cannot open the " + role + " for reading");
  std::string contents;
  char block[1 << 16];
  while (true) {
    const std::size_t n = std::fread(block, 1, sizeof(block), file.get());
    if (n == 0) break;
    if (contents.size() + n > max_bytes) {
      return InvalidArgument(path + ": the file grew while being read and" + too_large);
    }
    contents.append(block, n);
  }
  if (std::ferror(file.get())) return IoError(path + ": reading the " + role + " failed");
  if (text) {
    if (const std::size_t nul = contents.find('\0'); nul != std::string::npos) {
      return ParseError(path + ": holds binary data (a NUL byte at byte " + std::to_string(nul) +
                        ") where a text " + role + " was expected; is this the right file?");
    }
  }
  return contents;
}

std::string PrintableExcerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  const std::size_t n = std::min(text.size(), max_chars);
  out.reserve(n + 3);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    out += (c >= 0x20 && c < 0x7f) || c == '\t' ? static_cast<char>(c) : '?';
  }
  if (text.size() > max_chars) out += "...";
  return out;
}

}  // namespace aavio::io
