#include "aavio/io/ply.hpp"

#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "aavio/common/format.hpp"

namespace aavio::io {
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

void WriteHeader(std::ostream& out, const std::string& comment, std::size_t vertices) {
  out << "ply\nformat binary_little_endian 1.0\n";
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);)
    out << "comment " << line << "\n";
  out << "element vertex " << vertices << "\n";
  for (const char* property : kProperties)
    out << property << "\n";
  out << "end_header\n";
}

void WriteVertices(std::ostream& out, std::span<const Eigen::Vector3f> points,
                   std::span<const Rgb> colours) {
  for (std::size_t i = 0; i < points.size(); ++i) {
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

PlyWriter::PlyWriter(std::string path, std::string comment, std::ofstream part)
    : path_(std::move(path)), comment_(std::move(comment)), part_(std::move(part)) {}

Expected<PlyWriter> PlyWriter::Open(const std::string& path, std::string comment) {
  std::ofstream part(path + ".part", std::ios::binary | std::ios::trunc);
  if (!part) return IoError(path + ".part: cannot write");
  return PlyWriter(path, std::move(comment), std::move(part));
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

Status PlyWriter::Close() {
  if (!part_.is_open()) return FailedPrecondition(path_ + ": already closed");
  part_.close();
  if (!part_) return IoError(path_ + ".part: write failed (disk full?)");
  const std::string part_path = path_ + ".part";
  std::ifstream vertices(part_path, std::ios::binary);
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  if (!vertices) return IoError(part_path + ": cannot read back");
  if (!out) return IoError(path_ + ": cannot write");
  WriteHeader(out, comment_, size_);
  if (size_ > 0) out << vertices.rdbuf();
  if (!out) return IoError(path_ + ": write failed (disk full?)");
  vertices.close();
  std::remove(part_path.c_str());
  return Status::Ok();
}

Expected<ColouredCloud> ReadPly(const std::string& path) {
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
  constexpr long long kVertexBytes = 3 * sizeof(float) + 3;
  const std::streamoff body_start = in.tellg();
  in.seekg(0, std::ios::end);
  const long long body_bytes = static_cast<long long>(in.tellg() - body_start);
  in.seekg(body_start);
  if (vertices > body_bytes / kVertexBytes) {
    return ParseError(
        StrFormat("%s: the header declares %lld vertices but the file holds %lld "
                  "(%lld bytes of %lld each); the file is cut short or its header is wrong",
                  path.c_str(), vertices, body_bytes / kVertexBytes, body_bytes, kVertexBytes));
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

}  // namespace aavio::io
