#include "aavio/io/ply.hpp"

#include <cctype>
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

}  // namespace

Status WritePly(const std::string& path, std::span<const Eigen::Vector3f> points,
                std::span<const Rgb> colours, const std::string& comment) {
  if (points.size() != colours.size()) {
    return InvalidArgument(
        StrFormat("%s: %zu points but %zu colours", path.c_str(), points.size(), colours.size()));
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return IoError(path + ": cannot write");
  out << "ply\nformat binary_little_endian 1.0\n";
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);)
    out << "comment " << line << "\n";
  out << "element vertex " << points.size() << "\n";
  for (const char* property : kProperties)
    out << property << "\n";
  out << "end_header\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    out.write(reinterpret_cast<const char*>(points[i].data()), 3 * sizeof(float));
    out.write(reinterpret_cast<const char*>(colours[i].data()), 3);
  }
  return out ? Status::Ok() : IoError(path + ": write failed (disk full?)");
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
