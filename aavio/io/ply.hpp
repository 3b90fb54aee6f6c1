#pragma once
/// Coloured point clouds as PLY files (binary little endian, `float x y z` + `uchar red green
/// blue` per vertex): what `aavio run` writes as map.ply, and reads back for tests and tools.
/// MeshLab, CloudCompare, Open3D and PCL open these files.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio::io {

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

/// Reads a file in the layout WritePly writes (other PLY layouts are refused with what was found).
Expected<ColouredCloud> ReadPly(const std::string& path);

}  // namespace aavio::io
