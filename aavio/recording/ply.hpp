#pragma once
/// Coloured point clouds as PLY files (binary little endian, `float x y z` + `uchar red green
/// blue` per vertex): what `aavio run` writes as map.ply, and reads back for tests and tools.
/// MeshLab, CloudCompare, Open3D and PCL open these files.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio::recording {

using Rgb = std::array<std::uint8_t, 3>;

struct ColouredCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Rgb> colours;  ///< one per point
  std::string comment;       ///< the header's `comment` lines, joined by newlines
};

/// Writes (truncating); `colours` must have one entry per point. `comment` goes into the header
/// (one `comment` line per line of it).
Status WritePly(const std::string& path, std::span<const Eigen::Vector3f> points,
                std::span<const Rgb> colours, const std::string& comment = "");

/// Writes a PLY file (the layout above) a batch of points at a time, for clouds too large to hold:
/// the header and the vertices go to `<path>.part` as they come; Close() writes the count into the
/// header in place (no copy: it needs no more disk) and renames the file to `path`. After a failed
/// write (a full disk) Close() still leaves a valid `path` with the vertices that reached the disk,
/// and says how many. A writer not closed leaves only the part file.
class PlyWriter {
 public:
  /// Creates `<path>.part` (truncating).
  static Expected<PlyWriter> Open(const std::string& path, const std::string& comment = "");
  /// `colours` must have one entry per point.
  Status Append(std::span<const Eigen::Vector3f> points, std::span<const Rgb> colours);
  /// Completes the file: its count written, `<path>.part` renamed to `path`. With `rotation`,
  /// every point is first turned by it (a change of world frame, e.g. to gravity's z up),
  /// in place, a block at a time.
  Status Close(const std::optional<Eigen::Matrix3d>& rotation = std::nullopt);
  std::size_t size() const { return size_; }

 private:
  PlyWriter(std::string path, std::ofstream part, std::size_t count_at, std::size_t header_bytes);
  std::string path_;
  std::ofstream part_;
  std::size_t count_at_ = 0;      ///< offset of the header's count lines
  std::size_t header_bytes_ = 0;  ///< where the vertices start
  std::size_t size_ = 0;
};

/// Reads a file in the layout WritePly writes (other PLY layouts are refused with what was found).
Expected<ColouredCloud> ReadPly(const std::string& path);

}  // namespace aavio::recording
