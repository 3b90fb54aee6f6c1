#pragma once
/// What a path is, and bounded reading of files that are read whole. Every reader asks here first,
/// so a folder, a named pipe, a device or a link loop is refused by its kind before a byte is read,
/// and a file read whole has a size limit that the error names.

#include <cstdint>
#include <string>

#include "aavio/common/status.hpp"

namespace aavio::io {

/// Limit of a settings file read whole: a calibration, a configuration, a sequence.yaml, a sensor
/// description, a summary.json. The largest real ones are a few kB.
inline constexpr std::uint64_t kMaxSettingsFileBytes = 16ull << 20;
/// Limit of a trajectory read whole (about 2.5 million poses: 1 kHz motion capture for 40 min).
inline constexpr std::uint64_t kMaxTrajectoryFileBytes = 256ull << 20;

/// Ok when `path` is a regular file, after following links. Otherwise says what it is instead
/// (missing, a dangling link or a link loop, a folder, a named pipe, a device, a socket) and what
/// to give. `role` names what the file was meant to be, e.g. "calibration file".
Status CheckRegularFile(const std::string& path, const std::string& role);

/// Reads a whole regular file of at most `max_bytes`. A larger file is refused with its size and
/// the limit; so is one that holds a NUL byte when `text` is set (binary data where text belongs).
Expected<std::string> ReadBoundedFile(const std::string& path, std::uint64_t max_bytes,
                                      const std::string& role, bool text = true);

/// A piece of a line of a file, safe to print: at most `max_chars` characters, anything not
/// printable ASCII shown as '?', "..." when cut.
std::string PrintableExcerpt(std::string_view text, std::size_t max_chars = 80);

}  // namespace aavio::io
