#pragma once
// Helpers of the fuzz targets (one per parser, see CMakeLists.txt): the readers take paths, so
// each input is written to a file of this process first; then everything the reader offers is
// read. A target only checks that the reader neither crashes, hangs, leaks nor trips a sanitizer:
// a refused file is a correct answer.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "aavio/io/streams.hpp"

namespace aavio::fuzz {

/// A file per process and name, under the system's temporary folder, rewritten per input; the
/// folder is removed when the process exits.
inline std::string WriteInput(const std::string& name, const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("aavio_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(
          std::filesystem::temp_directory_path() / ("aavio_fuzz_" + std::to_string(::getpid())),
          ec);
    });
    return d;
  }();
  const std::filesystem::path path = dir / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path.string();
}

/// Splits an input made of several files at a line "--8<--" (the first one only); without the
/// line both parts are the whole input.
inline std::pair<std::string_view, std::string_view> SplitTwo(const std::uint8_t* data,
                                                              std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view kCut = "\n--8<--\n";
  const std::size_t at = all.find(kCut);
  if (at == std::string_view::npos) return {all, all};
  return {all.substr(0, at), all.substr(at + kCut.size())};
}

inline std::string WriteText(const std::string& name, std::string_view text) {
  return WriteInput(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

/// Reads a stream to its end in 10 ms steps (as the sequence reader does), then seeks back to
/// its first element and reads once more; stops at the first error.
template <typename T>
void Drain(io::Stream<T>& stream) {
  std::vector<T> out;
  const TimeNs first_ns = stream.info().t_first_ns;
  TimeNs t_ns = first_ns;
  for (int step = 0; step < 100000 && !stream.AtEnd(); ++step) {
    // Past the data's clock range the rest is read in one call.
    t_ns = (t_ns > std::numeric_limits<TimeNs>::max() - 10 * kNsPerMs)
               ? std::numeric_limits<TimeNs>::max()
               : t_ns + 10 * kNsPerMs;
    if (step > 200) t_ns = std::numeric_limits<TimeNs>::max();
    out.clear();
    if (!stream.ReadUntil(t_ns, &out).ok()) return;
  }
  if (!stream.Seek(first_ns).ok()) return;
  out.clear();
  (void)stream.ReadUntil(std::numeric_limits<TimeNs>::max(), &out);
}

/// Bounds of the reads: a fuzz input is small, so a reader that keeps producing from it is
/// producing from nothing (still bounded by the sensor check and the time-order policy).
inline io::StreamOptions FuzzStreamOptions() {
  io::StreamOptions options;
  options.block_events = 4096;
  return options;
}

}  // namespace aavio::fuzz
