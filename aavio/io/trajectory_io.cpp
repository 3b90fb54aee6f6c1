#include "aavio/io/trajectory_io.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "aavio/io/config_yaml.hpp"
#include "aavio/io/file_checks.hpp"

namespace aavio::io {

namespace {

bool IsSeparator(char c) {
  return c == ' ' || c == '\t' || c == ',' || c == '\r';
}

}  // namespace

Expected<std::vector<geometry::StampedPose>> ParseTumTrajectory(const std::string& text,
                                                                const std::string& origin) {
  std::vector<geometry::StampedPose> poses;
  std::size_t line_number = 0;
  std::size_t previous_line = 0;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + begin, end - begin);
    begin = end + 1;
    ++line_number;
    const std::string where = origin + ":" + std::to_string(line_number);

    std::size_t i = 0;
    while (i < line.size() && IsSeparator(line[i]))
      ++i;
    if (i == line.size() || line[i] == '#') continue;

    std::array<std::string_view, 8> fields;
    std::size_t count = 0;
    while (i < line.size()) {
      std::size_t j = i;
      while (j < line.size() && !IsSeparator(line[j]))
        ++j;
      if (count < fields.size()) fields[count] = line.substr(i, j - i);
      ++count;
      i = j;
      while (i < line.size() && IsSeparator(line[i]))
        ++i;
    }
    if (count != 8) {
      return ParseError(where + ": expected 8 columns 'timestamp tx ty tz qx qy qz qw', found " +
                        std::to_string(count) + ": '" + PrintableExcerpt(line) + "'");
    }
    Expected<TimeNs> t_ns = ParseSecondsToNs(fields[0]);
    if (!t_ns) return ParseError(where + ": " + t_ns.status().message());
    std::array<double, 7> v{};
    for (std::size_t k = 0; k < 7; ++k) {
      const std::string_view f = fields[k + 1];
      auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v[k]);
      if (ec != std::errc() || ptr != f.data() + f.size() || !std::isfinite(v[k])) {
        static constexpr std::array<const char*, 7> kNames = {"tx", "ty", "tz", "qx",
                                                              "qy", "qz", "qw"};
        return ParseError(where + ": " + kNames[k] + " = '" + PrintableExcerpt(f, 40) +
                          "' is not a finite number");
      }
    }
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    const double norm = q.norm();
    if (!(std::abs(norm - 1.0) <= 0.01)) {
      char message[160];
      std::snprintf(message, sizeof(message),
                    ": quaternion (qx qy qz qw) has norm %.6g, not 1; is the column order "
                    "'timestamp tx ty tz qx qy qz qw'?",
                    norm);
      return ParseError(where + message);
    }
    if (!poses.empty() && *t_ns <= poses.back().t_ns) {
      return ParseError(where + ": timestamp " + std::string(fields[0]) +
                        (*t_ns == poses.back().t_ns ? " repeats" : " is before") +
                        " the one on line " + std::to_string(previous_line) +
                        "; stamps must increase (sort the file and drop duplicates)");
    }
    geometry::StampedPose pose;
    pose.t_ns = *t_ns;
    pose.T_world_body = {q.normalized().toRotationMatrix(), Eigen::Vector3d(v[0], v[1], v[2])};
    poses.push_back(pose);
    previous_line = line_number;
  }
  return poses;
}

Expected<std::vector<geometry::StampedPose>> ReadTumTrajectory(const std::string& path) {
  Expected<std::string> text = ReadBoundedFile(path, kMaxTrajectoryFileBytes, "trajectory file");
  if (!text) return text.status();
  return ParseTumTrajectory(*text, path);
}

std::string FormatTumPose(const geometry::StampedPose& pose) {
  const Eigen::Quaterniond q = pose.T_world_body.Quaternion();
  const Eigen::Vector3d& t = pose.T_world_body.t;
  char line[256];
  std::snprintf(line, sizeof(line), " %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", t.x(), t.y(), t.z(),
                q.x(), q.y(), q.z(), q.w());
  return FormatSecondsNs(pose.t_ns) + line;
}

std::string FormatTumTrajectory(const std::vector<geometry::StampedPose>& poses) {
  std::string out = kTumHeader;
  out.reserve(out.size() + poses.size() * 120);
  for (const geometry::StampedPose& pose : poses)
    out += FormatTumPose(pose);
  return out;
}

Status WriteTumTrajectory(const std::string& path,
                          const std::vector<geometry::StampedPose>& poses) {
  return WriteTextFile(path, FormatTumTrajectory(poses));
}

}  // namespace aavio::io
