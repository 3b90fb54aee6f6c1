#include "aavio/io/trajectory_writing.hpp"

#include <array>
#include <charconv>
#include <cstdio>
#include <filesystem>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/text_fields.hpp"
#include "aavio/io/trajectory_io.hpp"

namespace aavio::io {

Expected<TrajectoryFormat> WritableTrajectoryFormat(const std::string& name) {
  Expected<TrajectoryFormat> format = TrajectoryFormatNamed(name);
  if (format && *format != TrajectoryFormat::kAuto) return format;
  return InvalidArgument("trajectory format '" + name +
                         "' is none of tum, tum_ns, kitti, euroc, evslam");
}

std::string TrajectoryFileName(TrajectoryFormat format) {
  return std::string("trajectory_") + TrajectoryFormatName(format) +
         (format == TrajectoryFormat::kEuroc ? ".csv" : ".txt");
}

std::string FormatTrajectory(const std::vector<geometry::StampedPose>& poses,
                             const std::vector<geometry::StampedVelocity>& velocities,
                             TrajectoryFormat format) {
  if (format == TrajectoryFormat::kTum || format == TrajectoryFormat::kAuto)
    return FormatTumTrajectory(poses);
  const bool with_velocity = velocities.size() == poses.size();
  std::string out;
  if (format == TrajectoryFormat::kEuroc) {
    out =
        "#timestamp [ns],p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],"
        "q_RS_z [],v_RS_R_x [m s^-1],v_RS_R_y [m s^-1],v_RS_R_z [m s^-1]\n";
  } else if (format == TrajectoryFormat::kEvslam) {
    out = "# timestamp tx ty tz qx qy qz qw vx vy vz (velocity in the camera frame, m/s)\n";
  }
  char line[512];
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const geometry::RigidTransform& T = poses[i].T_world_body;
    const Eigen::Quaterniond q = T.Quaternion();
    const Eigen::Vector3d v_body =
        with_velocity ? velocities[i].v_body_mps : Eigen::Vector3d::Zero();
    switch (format) {
      case TrajectoryFormat::kKitti:
        std::snprintf(line, sizeof(line),
                      "%.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e %.9e\n", T.R(0, 0),
                      T.R(0, 1), T.R(0, 2), T.t.x(), T.R(1, 0), T.R(1, 1), T.R(1, 2), T.t.y(),
                      T.R(2, 0), T.R(2, 1), T.R(2, 2), T.t.z());
        out += line;
        break;
      case TrajectoryFormat::kEuroc: {
        const Eigen::Vector3d v = T.R * v_body;
        std::snprintf(line, sizeof(line),
                      "%lld,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f\n",
                      static_cast<long long>(poses[i].t_ns), T.t.x(), T.t.y(), T.t.z(), q.w(),
                      q.x(), q.y(), q.z(), v.x(), v.y(), v.z());
        out += line;
        break;
      }
      case TrajectoryFormat::kEvslam:
        std::snprintf(line, sizeof(line), " %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n",
                      T.t.x(), T.t.y(), T.t.z(), q.x(), q.y(), q.z(), q.w(), v_body.x(), v_body.y(),
                      v_body.z());
        out += FormatSecondsNs(poses[i].t_ns) + line;
        break;
      case TrajectoryFormat::kTumNs:
        std::snprintf(line, sizeof(line), "%lld %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n",
                      static_cast<long long>(poses[i].t_ns), T.t.x(), T.t.y(), T.t.z(), q.x(),
                      q.y(), q.z(), q.w());
        out += line;
        break;
      case TrajectoryFormat::kTum:
      case TrajectoryFormat::kAuto:
        break;
    }
  }
  return out;
}

Status WriteTrajectory(const std::string& path, const std::vector<geometry::StampedPose>& poses,
                       const std::vector<geometry::StampedVelocity>& velocities,
                       TrajectoryFormat format) {
  AAVIO_RETURN_IF_ERROR(WriteTextFile(path, FormatTrajectory(poses, velocities, format)));
  if (format != TrajectoryFormat::kKitti) return Status::Ok();
  std::string times;
  for (const geometry::StampedPose& p : poses)
    times += FormatSecondsNs(p.t_ns) + "\n";
  std::filesystem::path times_path(path);
  times_path.replace_filename(times_path.stem().string() + "_times.txt");
  return WriteTextFile(times_path.string(), times);
}

std::string FormatVelocities(const std::vector<geometry::StampedVelocity>& velocities) {
  std::string out = "# timestamp vx vy vz wx wy wz (camera frame; m/s, rad/s)\n";
  char line[256];
  for (const geometry::StampedVelocity& v : velocities) {
    std::snprintf(line, sizeof(line), " %.6f %.6f %.6f %.6f %.6f %.6f\n", v.v_body_mps.x(),
                  v.v_body_mps.y(), v.v_body_mps.z(), v.w_body_radps.x(), v.w_body_radps.y(),
                  v.w_body_radps.z());
    out += FormatSecondsNs(v.t_ns) + line;
  }
  return out;
}

Expected<std::vector<TimeNs>> ReadStamps(const std::string& path) {
  Expected<std::string> text = ReadBoundedFile(path, kMaxTrajectoryFileBytes, "stamps file");
  if (!text) return text.status();
  std::vector<std::string> fields;
  std::vector<std::size_t> lines;
  bool euroc_header = false;
  text::Lines text_lines(*text);
  std::string_view line;
  while (text_lines.Next(&line)) {
    if (text::IsSkipped(line)) {
      euroc_header = euroc_header || line.find("[ns]") != std::string_view::npos;
      continue;
    }
    std::array<std::string_view, 1> f;
    text::SplitFields(line, &f);
    fields.emplace_back(f[0]);
    lines.push_back(text_lines.number());
  }
  if (fields.empty()) return ParseError(path + ": no stamps (one per line, first column)");
  // Nanoseconds: integers, epoch-sized or stepping by 1000 and more (or a EuRoC [ns] header).
  bool integers = true;
  for (const std::string& f : fields)
    integers = integers && f.find_first_not_of("0123456789") == std::string::npos;
  bool ns = euroc_header;
  if (integers && !ns) {
    long long previous = 0;
    for (std::size_t i = 0; i < fields.size() && !ns; ++i) {
      long long v = 0;
      std::from_chars(fields[i].data(), fields[i].data() + fields[i].size(), v);
      ns = v >= 1'000'000'000'000LL || (i > 0 && v - previous >= 1000);
      previous = v;
    }
  }
  std::vector<TimeNs> stamps;
  stamps.reserve(fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string where = path + ":" + std::to_string(lines[i]);
    TimeNs t = 0;
    if (ns) {
      if (!text::ParseNumber(fields[i], &t) || t < 0)
        return ParseError(where + ": '" + fields[i] + "' is not a whole number of nanoseconds");
    } else {
      Expected<TimeNs> s = ParseSecondsToNs(fields[i]);
      if (!s) return ParseError(where + ": " + s.status().message());
      t = *s;
    }
    if (!stamps.empty() && t <= stamps.back()) {
      return ParseError(where + ": stamp " + fields[i] + " is not after the one before it; " +
                        "stamps must increase (sort the file and drop duplicates)");
    }
    stamps.push_back(t);
  }
  return stamps;
}

}  // namespace aavio::io
