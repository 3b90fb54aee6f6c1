// `aavio info` on data: an event file (.h5, .txt, .raw), a bag, or a whole sequence.
#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <sstream>

#include "aavio/common/format.hpp"
#include "aavio/events/event_statistics.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/formats/dsec_h5/dsec_h5_reader.hpp"
#include "aavio/io/formats/ros2_bag/ros2_bag.hpp"
#include "aavio/io/formats/rosbag/bag_streams.hpp"
#include "aavio/io/formats/rosbag/rosbag_messages.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/stream_stats.hpp"
#include "aavio/io/text_fields.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "info.hpp"

namespace aavio::cli {

namespace {

namespace fs = std::filesystem;

nlohmann::json EventJson(const io::EventStats& s, const io::StreamInfo& info) {
  nlohmann::json j = {{"events", s.count},
                      {"t_first_s", FormatSecondsNs(s.t_first_ns)},
                      {"t_last_s", FormatSecondsNs(s.t_last_ns)},
                      {"duration_s", NsToSeconds(s.t_last_ns - s.t_first_ns)},
                      {"mean_rate_ev_s", s.mean_rate_hz},
                      {"peak_rate_ev_s", s.peak_rate_hz},
                      {"source", info.description}};
  if (info.width > 0) j["resolution"] = {info.width, info.height};
  if (s.max_x >= 0) j["max_xy"] = {s.max_x, s.max_y};
  return j;
}

std::string EventText(const io::EventStats& s, const io::StreamInfo& info) {
  std::string text =
      StrFormat("%lld events, %s .. %s s (%.3f s), mean %.3f Mev/s, peak %.3f Mev/s",
                static_cast<long long>(s.count), FormatSecondsNs(s.t_first_ns).c_str(),
                FormatSecondsNs(s.t_last_ns).c_str(), NsToSeconds(s.t_last_ns - s.t_first_ns),
                s.mean_rate_hz * 1e-6, s.peak_rate_hz * 1e-6);
  if (info.width > 0) text += StrFormat(", %d x %d", info.width, info.height);
  if (s.max_x >= 0) text += StrFormat(", max x %d y %d", s.max_x, s.max_y);
  return text;
}

/// The sensor statistics of a stream (a second pass over it).
Status DescribeSensorStatistics(const io::SourceSpec& spec, const io::StreamOptions& options,
                                int width, int height, nlohmann::json* j, std::string* text) {
  Expected<std::unique_ptr<io::EventStream>> stream = io::OpenEventStream(spec, options);
  if (!stream) return stream.status();
  events::EventStatisticsAccumulator accumulator(width, height);
  std::vector<events::Event> block;
  TimeNs until = (*stream)->info().t_first_ns;
  while (!(*stream)->AtEnd()) {
    until += 100 * kNsPerMs;
    block.clear();
    AAVIO_RETURN_IF_ERROR((*stream)->ReadUntil(until, &block));
    accumulator.Add(block);
  }
  const events::EventStatistics s = accumulator.Finish();
  (*j)["stats"] = {{"rate_ev_s", s.rate_ev_s},
                   {"rate_ev_px_s", s.rate_ev_px_s},
                   {"rate_without_hot_ev_px_s", s.rate_without_hot_ev_px_s},
                   {"on_fraction", s.on_fraction},
                   {"active_pixel_share", s.active_pixel_share},
                   {"isolated_share", s.isolated_share},
                   {"hot_pixels", s.hot_pixels},
                   {"hot_pixel_share", s.hot_pixel_share},
                   {"hot_event_share", s.hot_event_share},
                   {"interval_p01_us", s.interval_p01_us},
                   {"interval_median_ms", s.interval_median_ms},
                   {"events_per_passage", s.events_per_passage},
                   {"sensor", {width, height}}};
  *text +=
      StrFormat("  %-16s %.3f Mev/s, %.3f ev/px/s (%.3f without hot pixels), ON %.2f\n", "stats",
                s.rate_ev_s * 1e-6, s.rate_ev_px_s, s.rate_without_hot_ev_px_s, s.on_fraction);
  *text += StrFormat("  %-16s %.1f %% of %d x %d pixels active, %.1f %% of events isolated\n", "",
                     100.0 * s.active_pixel_share, width, height, 100.0 * s.isolated_share);
  *text += StrFormat("  %-16s same-pixel interval 1st percentile %.0f us, median %.2f ms\n", "",
                     s.interval_p01_us, s.interval_median_ms);
  *text += StrFormat(
      "  %-16s %lld hot pixels (%.3f %%) with %.1f %% of events; %.2f events per "
      "edge passage\n",
      "", static_cast<long long>(s.hot_pixels), 100.0 * s.hot_pixel_share,
      100.0 * s.hot_event_share, s.events_per_passage);
  return Status::Ok();
}

Status DescribeEvents(const std::string& label, const io::SourceSpec& spec,
                      const io::StreamOptions& options, bool with_stats, nlohmann::json* j,
                      std::string* text) {
  Expected<std::unique_ptr<io::EventStream>> stream = io::OpenEventStream(spec, options);
  if (!stream) return stream.status();
  Expected<io::EventStats> stats = io::ComputeEventStats(**stream);
  if (!stats) return stats.status();
  (*j)[label] = EventJson(*stats, (*stream)->info());
  *text += StrFormat("  %-16s %s\n", label.c_str(), EventText(*stats, (*stream)->info()).c_str());
  *text += StrFormat("  %-16s %s\n", "", (*stream)->info().description.c_str());
  if (!with_stats || stats->count == 0) return Status::Ok();
  // The sensor's size: the file's (or calibration's), else the largest coordinates seen.
  const io::StreamInfo& info = (*stream)->info();
  const int width = options.width > 0 ? options.width
                    : info.width > 0  ? info.width
                                      : stats->max_x + 1;
  const int height = options.height > 0 ? options.height
                     : info.height > 0  ? info.height
                                        : stats->max_y + 1;
  return DescribeSensorStatistics(spec, options, width, height, &(*j)[label], text);
}

Status DescribeImu(const io::SourceSpec& spec, const io::StreamOptions& options, nlohmann::json* j,
                   std::string* text) {
  Expected<std::unique_ptr<io::ImuStream>> stream = io::OpenImuStream(spec, options);
  if (!stream) return stream.status();
  Expected<io::ImuStats> stats = io::ComputeImuStats(**stream);
  if (!stats) return stats.status();
  (*j)["imu"] = {{"samples", stats->count},
                 {"rate_hz", stats->rate_hz},
                 {"t_first_s", FormatSecondsNs(stats->t_first_ns)},
                 {"t_last_s", FormatSecondsNs(stats->t_last_ns)},
                 {"source", (*stream)->info().description}};
  *text += StrFormat("  %-16s %lld samples at %.1f Hz, %s .. %s s\n", "imu",
                     static_cast<long long>(stats->count), stats->rate_hz,
                     FormatSecondsNs(stats->t_first_ns).c_str(),
                     FormatSecondsNs(stats->t_last_ns).c_str());
  return Status::Ok();
}

Status DescribeBag(const std::string& path, bool with_stats, nlohmann::json* j, std::string* text) {
  Expected<std::unique_ptr<io::rosbag::BagFile>> bag = io::rosbag::BagFile::Open(path);
  if (!bag) return bag.status();
  (*j)["kind"] = "bag";
  *text += "bag  " + path + "\n  topics           " + io::DescribeBagTopics(**bag) + "\n";
  nlohmann::json topics = nlohmann::json::object();
  std::set<std::string> seen;
  for (const io::rosbag::Connection& c : (*bag)->connections()) {
    if (!seen.insert(c.topic).second) continue;
    topics[c.topic] = {{"type", c.type}, {"md5sum", c.md5sum}};
    if (c.md5sum == io::rosbag::kEventArray.md5sum ||
        c.md5sum == io::rosbag::kLegacyEventArrayMd5) {
      AAVIO_RETURN_IF_ERROR(DescribeEvents(c.topic, {io::SourceFormat::kBag, path, c.topic, {}}, {},
                                           with_stats, j, text));
    } else if (c.md5sum == io::rosbag::kImu.md5sum) {
      AAVIO_RETURN_IF_ERROR(DescribeImu({io::SourceFormat::kBag, path, c.topic, {}}, {}, j, text));
    }
  }
  (*j)["topics"] = topics;
  return Status::Ok();
}

Status DescribeRos2Bag(const std::string& path, bool with_stats, nlohmann::json* j,
                       std::string* text) {
  Expected<std::vector<io::Ros2EventTopic>> topics = io::ListRos2EventTopics(path);
  if (!topics) return topics.status();
  (*j)["kind"] = "ros2_bag";
  *text += "ROS 2 bag  " + path + "\n";
  if (topics->empty()) *text += "  no event_camera_msgs/msg/EventPacket topic\n";
  for (const io::Ros2EventTopic& t : *topics) {
    *text += StrFormat("  %-16s %lld EventPacket messages, encoding %s\n", t.name.c_str(),
                       static_cast<long long>(t.messages), t.encoding.c_str());
    AAVIO_RETURN_IF_ERROR(DescribeEvents(t.name, {io::SourceFormat::kRos2Bag, path, t.name, {}}, {},
                                         with_stats, j, text));
  }
  return Status::Ok();
}

Status DescribeSequenceData(const io::SequenceDescription& d, bool with_stats, nlohmann::json* j,
                            std::string* text) {
  (*j)["kind"] = "sequence";
  (*j)["name"] = d.name;
  *text += "sequence  " + d.name + "  (" + d.origin + ")\n";
  io::StreamOptions options;
  if (!d.calibration.empty()) {
    Expected<io::LoadedCalibration> calib = io::LoadCalibration(d.calibration);
    if (!calib) return calib.status();
    const geometry::StereoRig& rig = calib->rig;
    options.width = rig.width();
    options.height = rig.height();
    (*j)["calibration"] = {{"path", d.calibration},
                           {"resolution", {rig.width(), rig.height()}},
                           {"focal_px", rig.focal_px()},
                           {"baseline_m", rig.baseline_m()}};
    *text += StrFormat("  %-16s %d x %d px, f %.3f px, baseline %.4f m  (%s)\n", "calibration",
                       rig.width(), rig.height(), rig.focal_px(), rig.baseline_m(),
                       d.calibration.c_str());
  } else {
    *text += StrFormat("  %-16s none given\n", "calibration");
  }
  AAVIO_RETURN_IF_ERROR(DescribeEvents("left", d.left, options, with_stats, j, text));
  AAVIO_RETURN_IF_ERROR(DescribeEvents("right", d.right, options, with_stats, j, text));
  if (d.imu) {
    AAVIO_RETURN_IF_ERROR(DescribeImu(*d.imu, options, j, text));
  } else {
    *text += StrFormat("  %-16s none\n", "imu");
  }
  if (d.gt_trajectory) {
    Expected<std::vector<geometry::StampedPose>> poses = io::ReadGroundTruthPoses(*d.gt_trajectory);
    if (!poses) return poses.status();
    (*j)["ground_truth"] = {{"poses", poses->size()}, {"path", d.gt_trajectory->path}};
    *text += StrFormat("  %-16s %zu poses (%s)\n", "ground truth", poses->size(),
                       d.gt_trajectory->path.c_str());
  }
  if (!d.gt_depth.empty()) {
    (*j)["ground_truth_depth"] = d.gt_depth;
    *text += StrFormat("  %-16s %s\n", "gt depth", d.gt_depth.c_str());
  }
  return Status::Ok();
}

/// A rosbag2 folder: metadata.yaml beside its storage files.
bool IsRos2BagFolder(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec) && fs::is_regular_file(p / "metadata.yaml", ec) &&
         !fs::is_regular_file(p / "sequence.yaml", ec);
}

}  // namespace

// What a text file holds, from its first data line's columns: events `t x y p` (4), an IMU
// `t ax ay az gx gy gz` (7) or a TUM trajectory `t x y z qx qy qz qw` (8).
enum class TextKind { kEvents, kImu, kTrajectory };

Expected<TextKind> KindOfTextFile(const std::string& path) {
  AAVIO_RETURN_IF_ERROR(io::CheckRegularFile(path, "text file"));
  // The first line that is not a comment, within the file's first 64 kB.
  std::ifstream file(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  file.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file.gcount()));
  std::istringstream in(head);
  std::string line;
  for (int k = 0; std::getline(in, line); ++k) {
    if (io::text::IsSkipped(line)) continue;
    std::array<std::string_view, 1> first;
    const std::size_t columns = io::text::SplitFields(line, &first);  // as the readers split
    if (columns == 4) return TextKind::kEvents;
    if (columns == 7) return TextKind::kImu;
    if (columns == 8) return TextKind::kTrajectory;
    return InvalidArgument(StrFormat(
        "%s, line %d: %d columns, which no text file aavio reads has: events 't x y p' (4), an "
        "IMU 't ax ay az gx gy gz' (7) or a TUM trajectory 't x y z qx qy qz qw' (8)",
        path.c_str(), k + 1, static_cast<int>(columns)));
  }
  return TextKind::kEvents;  // empty: the event reader says so
}

Status DescribeTrajectory(const std::string& path, nlohmann::json* j, std::string* text) {
  // Stamps in seconds or nanoseconds, as `aavio eval` reads them.
  Expected<std::vector<geometry::StampedPose>> poses =
      io::ReadTrajectory(path, io::TrajectoryFormat::kAuto);
  if (!poses) return poses.status();
  double length_m = 0.0;
  for (std::size_t i = 1; i < poses->size(); ++i)
    length_m += ((*poses)[i].T_world_body.t - (*poses)[i - 1].T_world_body.t).norm();
  const TimeNs first = poses->empty() ? 0 : poses->front().t_ns;
  const TimeNs last = poses->empty() ? 0 : poses->back().t_ns;
  const double span_s = NsToSeconds(last - first);
  (*j)["kind"] = "trajectory";
  (*j)["trajectory"] = {{"poses", poses->size()},
                        {"t_first_s", FormatSecondsNs(first)},
                        {"t_last_s", FormatSecondsNs(last)},
                        {"rate_hz", span_s > 0 ? (poses->size() - 1) / span_s : 0.0},
                        {"path_length_m", length_m}};
  *text += "trajectory  " + path + "\n";
  *text += StrFormat("  %-16s %zu poses at %.1f Hz, %s .. %s s, path %.3f m\n", "poses",
                     poses->size(), span_s > 0 ? (poses->size() - 1) / span_s : 0.0,
                     FormatSecondsNs(first).c_str(), FormatSecondsNs(last).c_str(), length_m);
  return Status::Ok();
}

bool LooksLikeData(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  if (IsRos2BagFolder(p)) return true;
  if (fs::is_directory(p, ec)) {
    return fs::is_regular_file(p / "sequence.yaml", ec) ||
           fs::is_regular_file(p / "events" / "left" / "events.h5", ec);
  }
  const std::string ext = p.extension().string();
  if (ext == ".h5" || ext == ".hdf5" || ext == ".bag" || ext == ".txt" || ext == ".raw" ||
      ext == ".db3" || ext == ".mcap" || ext == ".aedat4") {
    return true;
  }
  return p.filename() == "sequence.yaml";
}

Status DescribeData(const std::string& path, bool stats, nlohmann::json* j, std::string* text) {
  (*j)["path"] = path;
  const fs::path p(path);
  const std::string ext = p.extension().string();
  if (ext == ".bag") return DescribeBag(path, stats, j, text);
  if (ext == ".db3" || ext == ".mcap" || IsRos2BagFolder(p))
    return DescribeRos2Bag(path, stats, j, text);
  if (ext == ".aedat4") {
    (*j)["kind"] = "aedat4";
    *text += "AEDAT4  " + path + "\n";
    const io::SourceSpec events{io::SourceFormat::kAedat4, path, "", {}};
    AAVIO_RETURN_IF_ERROR(DescribeEvents("events", events, {}, stats, j, text));
    // The IMU stream, when the recording has one.
    if (io::OpenImuStream(events, {}).ok()) AAVIO_RETURN_IF_ERROR(DescribeImu(events, {}, j, text));
    return Status::Ok();
  }
  if (ext == ".h5" || ext == ".hdf5") {
    if (Expected<cv::Mat> map = io::ReadDsecRectifyMap(path); map.ok()) {
      (*j)["kind"] = "rectify_map";
      (*j)["resolution"] = {map->cols, map->rows};
      *text += StrFormat("rectify_map  %s\n  %d x %d raw pixels -> rectified (x, y)\n",
                         path.c_str(), map->cols, map->rows);
      return Status::Ok();
    }
    (*j)["kind"] = "events";
    *text += "events  " + path + "\n";
    return DescribeEvents("events", {io::SourceFormat::kDsecH5, path, "", {}}, {}, stats, j, text);
  }
  if (ext == ".txt") {
    Expected<TextKind> kind = KindOfTextFile(path);
    if (!kind) return kind.status();
    if (*kind == TextKind::kImu) {
      (*j)["kind"] = "imu";
      *text += "imu  " + path + "\n";
      return DescribeImu({io::SourceFormat::kText, path, "", {}}, {}, j, text);
    }
    if (*kind == TextKind::kTrajectory) return DescribeTrajectory(path, j, text);
  }
  if (ext == ".txt" || ext == ".raw") {
    (*j)["kind"] = "events";
    *text += "events  " + path + "\n";
    const io::SourceFormat format =
        ext == ".txt" ? io::SourceFormat::kText : io::SourceFormat::kPropheseeRaw;
    return DescribeEvents("events", {format, path, "", {}}, {}, stats, j, text);
  }
  Expected<io::SequenceDescription> d = io::DescribeSequence(path);
  if (!d) return d.status();
  return DescribeSequenceData(*d, stats, j, text);
}

}  // namespace aavio::cli
