#include "aavio/io/trajectory_io.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "aavio/io/config_yaml.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/text_fields.hpp"

namespace aavio::io {

const char* TrajectoryFormatName(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::kAuto:
      return "auto";
    case TrajectoryFormat::kTum:
      return "tum";
    case TrajectoryFormat::kTumNs:
      return "tum_ns";
    case TrajectoryFormat::kEuroc:
      return "euroc";
    case TrajectoryFormat::kEvslam:
      return "evslam";
    case TrajectoryFormat::kKitti:
      return "kitti";
  }
  return "?";
}

Expected<TrajectoryFormat> TrajectoryFormatNamed(const std::string& name) {
  for (TrajectoryFormat f :
       {TrajectoryFormat::kAuto, TrajectoryFormat::kTum, TrajectoryFormat::kTumNs,
        TrajectoryFormat::kEuroc, TrajectoryFormat::kEvslam, TrajectoryFormat::kKitti}) {
    if (name == TrajectoryFormatName(f)) return f;
  }
  return InvalidArgument(
      "trajectory format '" + name +
      "' is none of auto, tum (seconds), tum_ns (nanosecond stamps), euroc, evslam, kitti");
}

namespace {

using text::IsSkipped;
using text::ParseNumber;
using text::SplitFields;

bool IsInteger(std::string_view f) {
  return !f.empty() && f.find_first_not_of("0123456789") == std::string_view::npos;
}

// The layout of a trajectory's text, told from its header and data (TrajectoryFormat::kAuto).
Expected<TrajectoryFormat> DetectFormat(const std::string& text) {
  bool euroc_header = false;
  std::vector<std::string_view> stamps;
  text::Lines lines(text);
  std::string_view line;
  while (stamps.size() < 50 && lines.Next(&line)) {
    if (IsSkipped(line)) {
      euroc_header = euroc_header || line.find("q_RS_w") != std::string_view::npos ||
                     line.find("[ns]") != std::string_view::npos;
      continue;
    }
    std::array<std::string_view, 20> f;
    const std::size_t n = SplitFields(line, &f);
    if (stamps.empty() && n == 12) return TrajectoryFormat::kKitti;
    // EvSLAM: TUM and a velocity, 11 columns with stamps in seconds; EuRoC's are integers.
    if (stamps.empty() && n == 11 && !euroc_header && !IsInteger(f[0]))
      return TrajectoryFormat::kEvslam;
    if (stamps.empty() && (euroc_header || n >= 11)) return TrajectoryFormat::kEuroc;
    stamps.push_back(f[0]);
  }
  // Nanosecond stamps: integers, and either epoch-sized (from 10^12) or steps of 1000 and more
  // (no trajectory is sampled once every 1000 s).
  const bool integers = !stamps.empty() && std::all_of(stamps.begin(), stamps.end(), IsInteger);
  if (!integers) return TrajectoryFormat::kTum;
  auto value = [](std::string_view f) {
    long long v = 0;
    std::from_chars(f.data(), f.data() + f.size(), v);
    return v;
  };
  bool ns = value(stamps.front()) >= 1'000'000'000'000LL;
  for (std::size_t i = 1; i < stamps.size(); ++i)
    ns = ns || value(stamps[i]) - value(stamps[i - 1]) >= 1000;
  return ns ? TrajectoryFormat::kTumNs : TrajectoryFormat::kTum;
}

// KITTI: the 3×4 [R|t] row by row per line; the stamps come from elsewhere (times.txt).
Expected<std::vector<geometry::StampedPose>> ParseKitti(const std::string& text,
                                                        const std::string& origin,
                                                        const std::vector<TimeNs>& stamps) {
  std::vector<geometry::StampedPose> poses;
  text::Lines lines(text);
  std::string_view line;
  while (lines.Next(&line)) {
    if (IsSkipped(line)) continue;
    const std::string where = origin + ":" + std::to_string(lines.number());
    std::array<std::string_view, 12> f;
    const std::size_t count = SplitFields(line, &f);
    if (count != 12) {
      return ParseError(where +
                        ": expected 12 columns (KITTI: the 3x4 matrix [R|t] row by row), "
                        "found " +
                        std::to_string(count) + ": '" + PrintableExcerpt(line) + "'");
    }
    std::array<double, 12> m{};
    for (std::size_t k = 0; k < 12; ++k) {
      if (!ParseNumber(f[k], &m[k]) || !std::isfinite(m[k]))
        return ParseError(where + ": column " + std::to_string(k + 1) + " = '" +
                          PrintableExcerpt(f[k], 40) + "' is not a finite number");
    }
    Eigen::Matrix3d R;
    R << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
    if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 0.01 && R.determinant() > 0))
      return ParseError(where + ": the 3x3 part is not a rotation (is this a KITTI pose file?)");
    if (stamps.empty()) {  // paired line by line: KITTI's 10 Hz
      geometry::StampedPose pose;
      pose.t_ns = static_cast<TimeNs>(poses.size()) * 100 * kNsPerMs;
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
      pose.T_world_body = {svd.matrixU() * svd.matrixV().transpose(),
                           Eigen::Vector3d(m[3], m[7], m[11])};
      poses.push_back(pose);
      continue;
    }
    if (poses.size() == stamps.size()) {
      return InvalidArgument(origin + ": more poses than the " + std::to_string(stamps.size()) +
                             " stamps given for it (--times): the two files must have a line "
                             "for each other");
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    geometry::StampedPose pose;
    pose.t_ns = stamps[poses.size()];
    pose.T_world_body = {svd.matrixU() * svd.matrixV().transpose(),
                         Eigen::Vector3d(m[3], m[7], m[11])};
    poses.push_back(pose);
  }
  if (!stamps.empty() && poses.size() != stamps.size()) {
    return InvalidArgument(origin + ": " + std::to_string(poses.size()) + " poses but " +
                           std::to_string(stamps.size()) +
                           " stamps given for it (--times): the two files must have a line for "
                           "each other");
  }
  return poses;
}

}  // namespace

Expected<TrajectoryFile> ParseTrajectoryFile(const std::string& text, const std::string& origin,
                                             TrajectoryFormat format,
                                             const std::vector<TimeNs>* kitti_stamps) {
  if (format == TrajectoryFormat::kAuto) {
    Expected<TrajectoryFormat> detected = DetectFormat(text);
    if (!detected) return detected.status();
    format = *detected;
  }
  TrajectoryFile file;
  file.format = format;
  if (format == TrajectoryFormat::kKitti) {
    if (!kitti_stamps) {
      return InvalidArgument(origin +
                             ": a KITTI pose file (12 columns) has no timestamps; give its "
                             "times.txt with --times (or two KITTI files of equal length, paired "
                             "line by line)");
    }
    Expected<std::vector<geometry::StampedPose>> poses = ParseKitti(text, origin, *kitti_stamps);
    if (!poses) return poses.status();
    file.poses = std::move(*poses);
    return file;
  }
  // Columns: TUM t x y z qx qy qz qw; EuRoC t[ns] x y z qw qx qy qz (and more after).
  // EvSLAM: TUM's columns, then vx vy vz (body frame).
  const bool euroc = format == TrajectoryFormat::kEuroc;
  const bool evslam = format == TrajectoryFormat::kEvslam;
  const bool ns_stamps = euroc || format == TrajectoryFormat::kTumNs;
  const std::size_t columns = evslam ? 11 : 8;
  const char* layout = euroc    ? "'timestamp[ns], x, y, z, qw, qx, qy, qz' (EuRoC)"
                       : evslam ? "'timestamp tx ty tz qx qy qz qw vx vy vz' (EvSLAM)"
                                : "'timestamp tx ty tz qx qy qz qw' (TUM)";
  std::vector<geometry::StampedPose>& poses = file.poses;
  std::size_t previous_line = 0;
  text::Lines lines(text);
  std::string_view line;
  while (lines.Next(&line)) {
    const std::size_t line_number = lines.number();
    if (IsSkipped(line)) continue;
    const std::string where = origin + ":" + std::to_string(line_number);
    std::array<std::string_view, 11> fields;
    const std::size_t count = SplitFields(line, &fields);
    if (euroc ? count < 8 : count != columns) {
      return ParseError(where + ": expected " + (euroc ? "at least " : "") +
                        std::to_string(columns) + " columns " + layout + ", found " +
                        std::to_string(count) + ": '" + PrintableExcerpt(line) + "'");
    }
    TimeNs t_ns = 0;
    if (ns_stamps) {
      const std::string_view f = fields[0];
      if (!ParseNumber(f, &t_ns) || t_ns < 0) {
        return ParseError(where + ": timestamp '" + PrintableExcerpt(f, 40) +
                          "' is not a whole number of nanoseconds" +
                          (euroc ? "" : "; for stamps in seconds use --format tum"));
      }
    } else {
      Expected<TimeNs> t = ParseSecondsToNs(fields[0]);
      if (!t) return ParseError(where + ": " + t.status().message());
      t_ns = *t;
    }
    std::array<double, 7> v{};
    for (std::size_t k = 0; k < 7; ++k) {
      const std::string_view f = fields[k + 1];
      if (!ParseNumber(f, &v[k]) || !std::isfinite(v[k])) {
        static constexpr std::array<const char*, 7> kTum = {"tx", "ty", "tz", "qx",
                                                            "qy", "qz", "qw"};
        static constexpr std::array<const char*, 7> kEuroc = {"x",  "y",  "z", "qw",
                                                              "qx", "qy", "qz"};
        return ParseError(where + ": " + (euroc ? kEuroc : kTum)[k] + " = '" +
                          PrintableExcerpt(f, 40) + "' is not a finite number");
      }
    }
    const Eigen::Quaterniond q = euroc ? Eigen::Quaterniond(v[3], v[4], v[5], v[6])
                                       : Eigen::Quaterniond(v[6], v[3], v[4], v[5]);
    const double norm = q.norm();
    if (!(std::abs(norm - 1.0) <= 0.01)) {
      char message[200];
      std::snprintf(message, sizeof(message),
                    ": the quaternion has norm %.6g, not 1; is the column order %s?", norm, layout);
      return ParseError(where + message);
    }
    if (!poses.empty() && t_ns <= poses.back().t_ns) {
      return ParseError(where + ": timestamp " + std::string(fields[0]) +
                        (t_ns == poses.back().t_ns ? " repeats" : " is before") +
                        " the one on line " + std::to_string(previous_line) +
                        "; stamps must increase (sort the file and drop duplicates)");
    }
    geometry::StampedPose pose;
    pose.t_ns = t_ns;
    pose.T_world_body = {q.normalized().toRotationMatrix(), Eigen::Vector3d(v[0], v[1], v[2])};
    poses.push_back(pose);
    previous_line = line_number;
    if (evslam) {
      Eigen::Vector3d velocity;
      for (int k = 0; k < 3; ++k) {
        if (!ParseNumber(fields[8 + k], &velocity[k]) || !std::isfinite(velocity[k]))
          return ParseError(where + ": v" + std::string(1, "xyz"[k]) + " = '" +
                            PrintableExcerpt(fields[8 + k], 40) + "' is not a finite number");
      }
      file.v_body_mps.push_back(velocity);
    }
  }
  return file;
}

Expected<std::vector<geometry::StampedPose>> ParseTrajectory(const std::string& text,
                                                             const std::string& origin,
                                                             TrajectoryFormat format) {
  Expected<TrajectoryFile> file = ParseTrajectoryFile(text, origin, format, nullptr);
  if (!file) return file.status();
  return std::move(file->poses);
}

Expected<TrajectoryFile> ReadTrajectoryFile(const std::string& path, TrajectoryFormat format,
                                            const std::vector<TimeNs>* kitti_stamps) {
  Expected<std::string> text = ReadBoundedFile(path, kMaxTrajectoryFileBytes, "trajectory file");
  if (!text) return text.status();
  return ParseTrajectoryFile(*text, path, format, kitti_stamps);
}

Expected<TrajectoryFormat> DetectTrajectoryFormat(const std::string& path) {
  Expected<std::string> text = ReadBoundedFile(path, kMaxTrajectoryFileBytes, "trajectory file");
  if (!text) return text.status();
  return DetectFormat(*text);
}

Expected<std::vector<geometry::StampedPose>> ParseTumTrajectory(const std::string& text,
                                                                const std::string& origin) {
  return ParseTrajectory(text, origin, TrajectoryFormat::kTum);
}

Expected<std::vector<geometry::StampedPose>> ReadTrajectory(const std::string& path,
                                                            TrajectoryFormat format) {
  Expected<std::string> text = ReadBoundedFile(path, kMaxTrajectoryFileBytes, "trajectory file");
  if (!text) return text.status();
  return ParseTrajectory(*text, path, format);
}

Expected<std::vector<geometry::StampedPose>> ReadTumTrajectory(const std::string& path) {
  return ReadTrajectory(path, TrajectoryFormat::kTum);
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
