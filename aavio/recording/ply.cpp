#include "aavio/recording/ply.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "aavio/common/format.hpp"
#include "aavio/io/file_checks.hpp"

namespace aavio::recording {
namespace {

constexpr const char* kProperties[] = {"property float x",     "property float y",
                                       "property float z",     "property uchar red",
                                       "property uchar green", "property uchar blue"};

// A header line for a message: at most 40 characters, anything unprintable as '?'.
std::string Quoted(const std::string& line) {
  std::string out = "\"";
  for (std::size_t i = 0; i < line.size() && i < 40; ++i)
    out += std::isprint(static_cast<unsigned char>(line[i])) ? line[i] : '?';
  return out + (line.size() > 40 ? "...\"" : "\"");
}

constexpr std::size_t kVertexBytes = 3 * sizeof(float) + 3;
// "element vertex N" and a comment padding it to a fixed width, so that a streamed file's count
// can be written over in place.
constexpr std::size_t kCountWidth = 20;

std::string CountLines(std::size_t vertices, bool padded) {
  std::string lines = "element vertex " + std::to_string(vertices) + "\n";
  if (padded) {
    const std::size_t digits = std::to_string(vertices).size();
    lines += "comment" + std::string(kCountWidth - std::min(digits, kCountWidth), ' ') + "\n";
  }
  return lines;
}

// Returns the header's offset of the count line.
std::size_t WriteHeader(std::ostream& out, const std::string& comment, std::size_t vertices,
                        bool padded = false) {
  std::string header = "ply\nformat binary_little_endian 1.0\n";
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);)
    header += "comment " + line + "\n";
  const std::size_t count_at = header.size();
  header += CountLines(vertices, padded);
  for (const char* property : kProperties)
    header += std::string(property) + "\n";
  header += "end_header\n";
  out << header;
  return count_at;
}

void WriteVertices(std::ostream& out, std::span<const Eigen::Vector3f> points,
                   std::span<const Rgb> colours) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    static_assert(kVertexBytes == 15);
    out.write(reinterpret_cast<const char*>(points[i].data()), 3 * sizeof(float));
    out.write(reinterpret_cast<const char*>(colours[i].data()), 3);
  }
}

}  // namespace

Status WritePly(const std::string& path, std::span<const Eigen::Vector3f> points,
                std::span<const Rgb> colours, const std::string& comment) {
  if (points.size() != colours.size()) {
    return InvalidArgument(
        StrFormat("%s: %zu points but %zu colours", path.c_str(), points.size(), colours.size()));
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return IoError(path + ": cannot write");
  WriteHeader(out, comment, points.size());
  WriteVertices(out, points, colours);
  return out ? Status::Ok() : IoError(path + ": write failed (disk full?)");
}

PlyWriter::PlyWriter(std::string path, std::ofstream part, std::size_t count_at,
                     std::size_t header_bytes)
    : path_(std::move(path)),
      part_(std::move(part)),
      count_at_(count_at),
      header_bytes_(header_bytes) {}

Expected<PlyWriter> PlyWriter::Open(const std::string& path, const std::string& comment) {
  std::ofstream part(path + ".part", std::ios::binary | std::ios::trunc);
  if (!part) return IoError(path + ".part: cannot write");
  const std::size_t count_at = WriteHeader(part, comment, 0, /*padded=*/true);
  const auto header_bytes = static_cast<std::size_t>(part.tellp());
  if (!part) return IoError(path + ".part: write failed (disk full?)");
  return PlyWriter(path, std::move(part), count_at, header_bytes);
}

Status PlyWriter::Append(std::span<const Eigen::Vector3f> points, std::span<const Rgb> colours) {
  if (points.size() != colours.size()) {
    return InvalidArgument(
        StrFormat("%s: %zu points but %zu colours", path_.c_str(), points.size(), colours.size()));
  }
  if (!part_.is_open()) return FailedPrecondition(path_ + ": already closed");
  WriteVertices(part_, points, colours);
  size_ += points.size();
  return part_ ? Status::Ok() : IoError(path_ + ".part: write failed (disk full?)");
}

namespace {

// Turns the `count` vertices from byte `offset` of an open file, a block at a time.
Status RotateVertices(std::fstream& file, std::size_t offset, std::size_t count,
                      const Eigen::Matrix3d& R, const std::string& path) {
  constexpr std::size_t kBlock = 65536;
  std::vector<char> block(kBlock * kVertexBytes);
  for (std::size_t done = 0; done < count;) {
    const std::size_t n = std::min(kBlock, count - done);
    const auto at = static_cast<std::streamoff>(offset + done * kVertexBytes);
    file.seekg(at);
    file.read(block.data(), static_cast<std::streamsize>(n * kVertexBytes));
    if (!file) return IoError(path + ": cannot read back its points to turn them");
    for (std::size_t i = 0; i < n; ++i) {
      char* vertex = block.data() + i * kVertexBytes;
      float xyz[3];
      std::memcpy(xyz, vertex, sizeof xyz);
      const Eigen::Vector3d p = R * Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
      for (int k = 0; k < 3; ++k)
        xyz[k] = static_cast<float>(p[k]);
      std::memcpy(vertex, xyz, sizeof xyz);
    }
    file.seekp(at);
    file.write(block.data(), static_cast<std::streamsize>(n * kVertexBytes));
    if (!file) return IoError(path + ": cannot write its turned points (disk full?)");
    done += n;
  }
  return Status::Ok();
}

}  // namespace

Status PlyWriter::Close(const std::optional<Eigen::Matrix3d>& rotation) {
  if (!part_.is_open()) return FailedPrecondition(path_ + ": already closed");
  part_.close();
  const std::string part_path = path_ + ".part";
  std::size_t complete = size_;
  std::string lost;
  if (!part_) {
    // A write failed (a full disk): keep the whole vertices that reached the file.
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(part_path, ec);
    if (ec || bytes < header_bytes_) return IoError(part_path + ": write failed (disk full?)");
    complete = std::min<std::size_t>(size_, (bytes - header_bytes_) / kVertexBytes);
    std::filesystem::resize_file(part_path, header_bytes_ + complete * kVertexBytes, ec);
    if (ec) return IoError(part_path + ": cannot truncate (" + ec.message() + ")");
    lost = StrFormat("%s: write failed (disk full?): %zu of %zu points written", path_.c_str(),
                     complete, size_);
  }
  {
    std::fstream file(part_path, std::ios::binary | std::ios::in | std::ios::out);
    if (rotation)
      AAVIO_RETURN_IF_ERROR(RotateVertices(file, header_bytes_, complete, *rotation, part_path));
    file.seekp(static_cast<std::streamoff>(count_at_));
    file << CountLines(complete, /*padded=*/true);
    if (!file) return IoError(part_path + ": cannot write its point count");
  }
  std::error_code ec;
  std::filesystem::rename(part_path, path_, ec);
  if (ec) return IoError(path_ + ": cannot rename " + part_path + " (" + ec.message() + ")");
  return lost.empty() ? Status::Ok() : IoError(lost);
}

Expected<ColouredCloud> ReadPly(const std::string& path) {
  AAVIO_RETURN_IF_ERROR(io::CheckRegularFile(path, "PLY point cloud"));
  std::ifstream in(path, std::ios::binary);
  if (!in) return NotFound(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line) || line != "ply") return ParseError(path + ": not a PLY file");
  if (!std::getline(in, line) || line != "format binary_little_endian 1.0") {
    return ParseError(path + ": " + Quoted(line) +
                      ": only binary_little_endian 1.0 is read (the layout aavio writes)");
  }
  ColouredCloud cloud;
  long long vertices = -1;
  std::size_t property = 0;
  while (std::getline(in, line) && line != "end_header") {
    if (line.rfind("comment", 0) == 0) {
      if (line.find_first_not_of(' ', 7) == std::string::npos) continue;  // padding
      if (!cloud.comment.empty()) cloud.comment += "\n";
      cloud.comment += line.size() > 8 ? line.substr(8) : "";
    } else if (line.rfind("element vertex ", 0) == 0) {
      std::istringstream n(line.substr(15));
      if (!(n >> vertices) || vertices < 0)
        return ParseError(path + ": " + Quoted(line) + ": bad vertex count");
    } else if (line.rfind("property", 0) == 0) {
      if (property >= std::size(kProperties) || line != kProperties[property]) {
        return ParseError(path + ": " + Quoted(line) +
                          ": expected float x y z and uchar red green blue, in that order");
      }
      ++property;
    } else {
      return ParseError(path + ": " + Quoted(line) + ": unexpected header line");
    }
  }
  if (line != "end_header") return ParseError(path + ": the header never ends (no end_header)");
  if (vertices < 0 || property != std::size(kProperties))
    return ParseError(path + ": the header lacks the vertex element or some of its properties");
  // The header's count against what the file holds, before anything is allocated for it.
  const auto vertex_bytes = static_cast<long long>(kVertexBytes);
  const std::streamoff body_start = in.tellg();
  in.seekg(0, std::ios::end);
  const long long body_bytes = static_cast<long long>(in.tellg() - body_start);
  in.seekg(body_start);
  if (vertices > body_bytes / vertex_bytes) {
    return ParseError(
        StrFormat("%s: the header declares %lld vertices but the file holds %lld "
                  "(%lld bytes of %lld each); the file is cut short or its header is wrong",
                  path.c_str(), vertices, body_bytes / vertex_bytes, body_bytes, vertex_bytes));
  }
  cloud.points.resize(static_cast<std::size_t>(vertices));
  cloud.colours.resize(static_cast<std::size_t>(vertices));
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    in.read(reinterpret_cast<char*>(cloud.points[i].data()), 3 * sizeof(float));
    in.read(reinterpret_cast<char*>(cloud.colours[i].data()), 3);
    if (!in) {
      return ParseError(
          StrFormat("%s: cut short at vertex %zu of %lld", path.c_str(), i, vertices));
    }
  }
  return cloud;
}

}  // namespace aavio::recording
