#include "aavio/io/sequence.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/formats/aedat4/aedat4.hpp"
#include "aavio/io/formats/dsec_h5/dsec_h5_reader.hpp"
#include "aavio/io/formats/prophesee_raw/prophesee_raw.hpp"
#include "aavio/io/formats/ros2_bag/ros2_bag.hpp"
#include "aavio/io/formats/rosbag/rosbag_messages.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/io/yaml_reading.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

const char* SourceFormatName(SourceFormat format) {
  switch (format) {
    case SourceFormat::kDsecH5:
      return "dsec_h5";
    case SourceFormat::kBag:
      return "bag";
    case SourceFormat::kText:
      return "text";
    case SourceFormat::kPropheseeRaw:
      return "prophesee_raw";
    case SourceFormat::kRos2Bag:
      return "ros2_bag";
    case SourceFormat::kAedat4:
      return "aedat4";
  }
  return "?";
}

Expected<SourceFormat> DetectSourceFormat(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".h5" || ext == ".hdf5") return SourceFormat::kDsecH5;
  if (ext == ".bag") return SourceFormat::kBag;
  if (ext == ".txt") return SourceFormat::kText;
  if (ext == ".raw") return SourceFormat::kPropheseeRaw;
  if (ext == ".db3" || ext == ".mcap") return SourceFormat::kRos2Bag;
  if (ext == ".aedat4") return SourceFormat::kAedat4;
  return InvalidArgument(path + ": unknown data format '" + ext +
                         "'; aavio reads DSEC-layout .h5, ROS1 .bag, text .txt, Prophesee .raw, "
                         "ROS 2 .db3 and iniVation .aedat4 files");
}

namespace {

std::string Resolve(const fs::path& base, const std::string& p) {
  if (p.empty()) return p;
  const fs::path path(p);
  return path.is_absolute() ? path.string() : (base / path).lexically_normal().string();
}

Status CheckKeys(const YAML::Node& node, const std::set<std::string>& known,
                 const std::string& where, const std::string& section) {
  if (!node.IsMap()) return ParseError(where + ": " + section + " must be a mapping");
  for (const auto& item : node) {
    if (!item.first.IsScalar()) {
      return ParseError(yaml::Where(where, item.first) + ": a key" +
                        (section.empty() ? "" : " under '" + section + "'") +
                        " is a list or a map, not a name");
    }
    const std::string key = item.first.Scalar();
    if (!known.count(key)) {
      std::vector<std::string> list(known.begin(), known.end());
      const std::string hint = config_detail::DidYouMean(key, list);
      return ParseError(yaml::Where(where, item.first) + ": unknown key '" + section + key + "'" +
                        (hint.empty() ? "" : "; did you mean '" + section + hint + "'?"));
    }
  }
  return Status::Ok();
}

std::string Scalar(const YAML::Node& node, const char* key) {
  return node[key] && node[key].IsScalar() ? node[key].Scalar() : std::string();
}

}  // namespace

Expected<SequenceDescription> ReadSequenceYaml(const std::string& path) {
  Expected<YAML::Node> root = yaml::LoadFile(path);
  if (!root) return root.status();
  const fs::path base = fs::path(path).parent_path();
  AAVIO_RETURN_IF_ERROR(CheckKeys(
      *root, {"name", "calibration", "events", "imu", "ground_truth", "format"}, path, ""));
  SequenceDescription d;
  d.origin = path;
  d.name = Scalar(*root, "name");
  if (d.name.empty()) d.name = fs::absolute(path).parent_path().filename().string();
  d.calibration = Resolve(base, Scalar(*root, "calibration"));

  Expected<YAML::Node> events =
      yaml::Child(*root, "events", path, "the left and right event files");
  if (!events) return events.status();
  AAVIO_RETURN_IF_ERROR(
      CheckKeys(*events, {"left", "right", "left_topic", "right_topic"}, path, "events."));
  for (auto [side, spec] : {std::pair{"left", &d.left}, std::pair{"right", &d.right}}) {
    const std::string file = Scalar(*events, side);
    if (file.empty()) {
      return NotFound(path + ": missing key 'events." + side + "' (the " + side + " event file)");
    }
    spec->path = Resolve(base, file);
    Expected<SourceFormat> format = DetectSourceFormat(spec->path);
    if (!format) return format.status().WithContext(path);
    spec->format = *format;
    const std::string topic_key = std::string(side) + "_topic";
    spec->topic = Scalar(*events, topic_key.c_str());
    const bool has_topics = spec->format == SourceFormat::kBag ||
                            spec->format == SourceFormat::kRos2Bag ||
                            spec->format == SourceFormat::kAedat4;
    if (!has_topics && !spec->topic.empty()) {
      return InvalidArgument(path + ": events." + topic_key + " names a topic, but " + spec->path +
                             " is a " + SourceFormatName(spec->format) +
                             " file, which has none; remove the key");
    }
    if (spec->topic.empty() && has_topics && spec->format != SourceFormat::kAedat4)
      spec->topic = std::string("/davis/") + side + "/events";
  }
  if (YAML::Node imu = (*root)["imu"]) {
    AAVIO_RETURN_IF_ERROR(CheckKeys(imu, {"path", "topic", "layout"}, path, "imu."));
    SourceSpec spec;
    spec.path = Resolve(base, Scalar(imu, "path"));
    if (spec.path.empty()) return NotFound(path + ": missing key 'imu.path'");
    Expected<SourceFormat> format = DetectSourceFormat(spec.path);
    if (!format) return format.status().WithContext(path);
    if (*format == SourceFormat::kDsecH5) {
      return InvalidArgument(path +
                             ": imu.path: IMU data are read from .txt, .bag or .aedat4 files");
    }
    spec.format = *format;
    spec.topic = Scalar(imu, "topic");
    if (spec.format == SourceFormat::kText && !spec.topic.empty()) {
      return InvalidArgument(path + ": imu.topic names a topic, but " + spec.path +
                             " is a text file, which has none; remove the key");
    }
    const std::string layout = Scalar(imu, "layout");
    if (layout == "tum_vie") {
      spec.imu_layout = ImuTextLayout::kTumVie;
    } else if (!layout.empty() && layout != "ecd") {
      return InvalidArgument(path + ": imu.layout '" + layout + "' must be ecd or tum_vie");
    }
    d.imu = spec;
  }
  if (YAML::Node gt = (*root)["ground_truth"]) {
    AAVIO_RETURN_IF_ERROR(
        CheckKeys(gt, {"trajectory", "topic", "depth", "calibration"}, path, "ground_truth."));
    if (!Scalar(gt, "trajectory").empty()) {
      SourceSpec spec;
      spec.path = Resolve(base, Scalar(gt, "trajectory"));
      const bool csv = fs::path(spec.path).extension() == ".csv";  // EuRoC
      Expected<SourceFormat> format = csv ? SourceFormat::kText : DetectSourceFormat(spec.path);
      if (!format || (*format != SourceFormat::kText && *format != SourceFormat::kBag)) {
        return InvalidArgument(path +
                               ": ground_truth.trajectory must be a TUM .txt, a EuRoC .csv or a "
                               "ROS1 .bag");
      }
      spec.format = *format;
      spec.topic = Scalar(gt, "topic");
      if (spec.format == SourceFormat::kText && !spec.topic.empty()) {
        return InvalidArgument(path + ": ground_truth.topic names a topic, but " + spec.path +
                               " is a text file, which has none; remove the key");
      }
      d.gt_trajectory = spec;
    }
    d.gt_depth = Resolve(base, Scalar(gt, "depth"));
    d.gt_calibration = Resolve(base, Scalar(gt, "calibration"));
  }
  return d;
}

Status WriteSequenceYaml(const std::string& path, const SequenceDescription& d) {
  const fs::path base = fs::absolute(path).parent_path();
  auto rel = [&](const std::string& p) {
    if (p.empty()) return p;
    const fs::path r = fs::absolute(p).lexically_relative(base);
    return (!r.empty() && r.native().rfind("..", 0) != 0) ? r.string() : fs::absolute(p).string();
  };
  std::vector<ConfigEntry> entries;
  auto add = [&](const std::string& key, const std::string& value) {
    if (!value.empty()) entries.push_back({key, {value, {}, false, ""}});
  };
  add("name", d.name);
  add("calibration", rel(d.calibration));
  add("events.left", rel(d.left.path));
  add("events.right", rel(d.right.path));
  if (d.left.format == SourceFormat::kBag) {
    add("events.left_topic", d.left.topic);
    add("events.right_topic", d.right.topic);
  }
  if (d.imu) {
    add("imu.path", rel(d.imu->path));
    if (d.imu->format == SourceFormat::kBag) add("imu.topic", d.imu->topic);
    if (d.imu->format == SourceFormat::kText) {
      add("imu.layout", d.imu->imu_layout == ImuTextLayout::kEcd ? "ecd" : "tum_vie");
    }
  }
  if (d.gt_trajectory) {
    add("ground_truth.trajectory", rel(d.gt_trajectory->path));
    if (d.gt_trajectory->format == SourceFormat::kBag)
      add("ground_truth.topic", d.gt_trajectory->topic);
  }
  add("ground_truth.depth", rel(d.gt_depth));
  add("ground_truth.calibration", rel(d.gt_calibration));
  return WriteTextFile(path,
                       FormatConfigYaml(entries, "aavio sequence description (keys: docs/io.md)"));
}

Expected<SequenceDescription> DescribeSequence(const std::string& path,
                                               const std::string& calibration) {
  std::error_code ec;
  const fs::path p(path);
  if (!fs::exists(p, ec)) return NotFound(path + ": no such file or folder");
  SequenceDescription d;
  if (fs::is_directory(p, ec)) {
    if (fs::is_regular_file(p / "sequence.yaml", ec)) {
      Expected<SequenceDescription> read = ReadSequenceYaml((p / "sequence.yaml").string());
      if (!read) return read.status();
      d = std::move(*read);
    } else if (fs::is_regular_file(p / "events" / "left" / "events.h5", ec)) {
      // A DSEC sequence folder as published (docs/io.md).
      d.origin = path;
      d.name = fs::absolute(p).lexically_normal().filename().string();
      d.left = {SourceFormat::kDsecH5, (p / "events" / "left" / "events.h5").string(), "", {}};
      d.right = {SourceFormat::kDsecH5, (p / "events" / "right" / "events.h5").string(), "", {}};
      if (fs::is_regular_file(p / "calibration" / "cam_to_cam.yaml", ec)) {
        d.calibration = (p / "calibration" / "cam_to_cam.yaml").string();
      }
      if (fs::is_directory(p / "disparity" / "event", ec))
        d.gt_depth = (p / "disparity" / "event").string();
      if (!fs::is_regular_file(d.right.path, ec)) {
        return NotFound(path + ": a DSEC folder needs events/right/events.h5 too");
      }
    } else {
      return NotFound(path +
                      ": no sequence here; expected sequence.yaml, or a DSEC sequence "
                      "folder (events/left/events.h5, events/right/events.h5, "
                      "calibration/cam_to_cam.yaml)");
    }
  } else if (p.filename() == "sequence.yaml" || p.extension() == ".yaml") {
    Expected<SequenceDescription> read = ReadSequenceYaml(path);
    if (!read) return read.status();
    d = std::move(*read);
  } else if (p.extension() == ".bag") {
    d.origin = path;
    d.name = p.stem().string();
    d.left = {SourceFormat::kBag, path, "/davis/left/events", {}};
    d.right = {SourceFormat::kBag, path, "/davis/right/events", {}};
    Expected<std::unique_ptr<rosbag::BagFile>> bag = rosbag::BagFile::Open(path);
    if (!bag) return bag.status();
    for (const rosbag::Connection& c : (*bag)->connections()) {
      if (c.md5sum == std::string(rosbag::kImu.md5sum) && !d.imu) {
        d.imu =
            SourceSpec{SourceFormat::kBag, path, "", {}};  // the only IMU topic, checked on open
      }
      if (c.md5sum == std::string(rosbag::kPoseStamped.md5sum) && !d.gt_trajectory) {
        d.gt_trajectory = SourceSpec{SourceFormat::kBag, path, "", {}};
      }
    }
  } else {
    return InvalidArgument(path +
                           ": not a sequence; give a sequence.yaml, a folder holding one, a "
                           "DSEC sequence folder or a .bag file");
  }
  if (!calibration.empty()) d.calibration = calibration;
  return d;
}

Expected<std::unique_ptr<EventStream>> OpenEventStream(const SourceSpec& spec,
                                                       const StreamOptions& options) {
  switch (spec.format) {
    case SourceFormat::kDsecH5: {
      auto s = DsecH5EventStream::Open(spec.path, options);
      if (!s) return s.status();
      return std::unique_ptr<EventStream>(std::move(*s));
    }
    case SourceFormat::kBag: {
      auto s = BagEventStream::Open(spec.path, spec.topic, options);
      if (!s) return s.status();
      return std::unique_ptr<EventStream>(std::move(*s));
    }
    case SourceFormat::kText: {
      auto s = TextEventStream::Open(spec.path, options);
      if (!s) return s.status();
      return std::unique_ptr<EventStream>(std::move(*s));
    }
    case SourceFormat::kPropheseeRaw: {
      auto s = PropheseeRawEventStream::Open(spec.path, options);
      if (!s) return s.status();
      return std::unique_ptr<EventStream>(std::move(*s));
    }
    case SourceFormat::kRos2Bag: {
      auto s = Ros2BagEventStream::Open(spec.path, spec.topic, options);
      if (!s) return s.status();
      return std::unique_ptr<EventStream>(std::move(*s));
    }
    case SourceFormat::kAedat4:
      return OpenAedat4EventStream(spec.path, spec.topic, options);
  }
  return InvalidArgument(spec.path + ": unknown format");
}

Expected<std::unique_ptr<ImuStream>> OpenImuStream(const SourceSpec& spec,
                                                   const StreamOptions& options) {
  if (spec.format == SourceFormat::kBag) {
    auto s = BagImuStream::Open(spec.path, spec.topic, options);
    if (!s) return s.status();
    return std::unique_ptr<ImuStream>(std::move(*s));
  }
  if (spec.format == SourceFormat::kText) {
    auto s = TextImuStream::Open(spec.path, spec.imu_layout, options);
    if (!s) return s.status();
    return std::unique_ptr<ImuStream>(std::move(*s));
  }
  if (spec.format == SourceFormat::kAedat4)
    return OpenAedat4ImuStream(spec.path, spec.topic, options);
  return InvalidArgument(spec.path + ": IMU data are read from .txt, .bag or .aedat4 files");
}

Expected<std::vector<geometry::StampedPose>> ReadGroundTruthPoses(const SourceSpec& spec) {
  if (spec.format == SourceFormat::kText) return ReadTrajectory(spec.path, TrajectoryFormat::kAuto);
  if (spec.format == SourceFormat::kBag) return ReadBagPoses(spec.path, spec.topic);
  return InvalidArgument(spec.path +
                         ": ground-truth poses are read from TUM or EuRoC text files and ROS1 "
                         "bags (geometry_msgs/PoseStamped); convert this one with `aavio convert`");
}

std::string DescribeSource(const SourceSpec& spec) {
  return spec.topic.empty() ? spec.path : spec.path + " (topic " + spec.topic + ")";
}

namespace {

bool SpanKnown(const StreamInfo& info) {
  return info.count != 0 && !(info.t_first_ns == 0 && info.t_last_ns == 0);
}

std::string Span(const StreamInfo& info) {
  return FormatSecondsNs(info.t_first_ns) + " - " + FormatSecondsNs(info.t_last_ns) + " s";
}

}  // namespace

Status CheckStreamsOverlap(const SequenceDescription& d, const StreamInfo& left,
                           const StreamInfo& right, const StreamInfo* imu) {
  const std::string where = d.origin.empty() ? d.left.path : d.origin;
  if (!SpanKnown(left) || !SpanKnown(right)) return Status::Ok();
  if (left.t_first_ns > right.t_last_ns || right.t_first_ns > left.t_last_ns) {
    return FailedPrecondition(where + ": the left camera's events span " + Span(left) +
                              " and the right camera's " + Span(right) +
                              ": they do not overlap; are both from this recording, and on one "
                              "clock?");
  }
  if (imu != nullptr && SpanKnown(*imu)) {
    const TimeNs first = std::min(left.t_first_ns, right.t_first_ns);
    const TimeNs last = std::max(left.t_last_ns, right.t_last_ns);
    if (imu->t_first_ns > last || imu->t_last_ns < first) {
      return FailedPrecondition(where + ": the IMU samples span " + Span(*imu) +
                                " and the events " + FormatSecondsNs(first) + " - " +
                                FormatSecondsNs(last) +
                                " s: they do not overlap; is the IMU on another clock (host "
                                "time against sensor time)? Fix its stamps, or leave it out");
    }
  }
  return Status::Ok();
}

std::string ImuStreamWarning(const SequenceDescription& d, std::int64_t samples, TimeNs first_ns,
                             TimeNs last_ns, double tick_rate_hz) {
  if (!d.imu) return "";
  const std::string name = d.imu->path + (d.imu->topic.empty() ? "" : " " + d.imu->topic);
  if (samples == 0) {
    return name +
           ": no IMU samples in the time processed; the run went on without an IMU "
           "(check the topic, the file or its stamps)";
  }
  if (samples < 2 || last_ns <= first_ns) return "";
  const double rate_hz = static_cast<double>(samples - 1) / NsToSeconds(last_ns - first_ns);
  if (rate_hz >= tick_rate_hz) return "";
  return name + StrFormat(
                    ": %.1f IMU samples per second, fewer than one per tick (%.0f Hz): the "
                    "rotation between ticks was interpolated from far-apart samples; an "
                    "IMU of 200 Hz or more is expected (downsampled, or the wrong topic?)",
                    rate_hz, tick_rate_hz);
}

Expected<std::unique_ptr<SequenceReader>> SequenceReader::Open(
    const SequenceDescription& d, const SequenceReaderOptions& options) {
  if (options.packet_ns <= 0) return InvalidArgument("packet length must be positive");
  if (options.passes < 1) return InvalidArgument("passes must be at least 1");
  std::error_code ec;
  if (d.left.topic == d.right.topic && fs::equivalent(d.left.path, d.right.path, ec)) {
    return InvalidArgument((d.origin.empty() ? d.left.path : d.origin) +
                           ": the left and the right camera both read " + d.left.path +
                           (d.left.topic.empty() ? "" : " topic " + d.left.topic) +
                           "; each camera needs its own events");
  }
  Expected<std::unique_ptr<EventStream>> left = OpenEventStream(d.left, options.stream);
  if (!left) return left.status();
  Expected<std::unique_ptr<EventStream>> right = OpenEventStream(d.right, options.stream);
  if (!right) return right.status();
  std::unique_ptr<ImuStream> imu;
  if (d.imu) {
    Expected<std::unique_ptr<ImuStream>> opened = OpenImuStream(*d.imu, options.stream);
    if (!opened) return opened.status();
    imu = std::move(*opened);
  }
  AAVIO_RETURN_IF_ERROR(
      CheckStreamsOverlap(d, (*left)->info(), (*right)->info(), imu ? &imu->info() : nullptr));
  return std::make_unique<SequenceReader>(std::move(*left), std::move(*right), std::move(imu),
                                          options);
}

SequenceReader::SequenceReader(std::unique_ptr<EventStream> left,
                               std::unique_ptr<EventStream> right, std::unique_ptr<ImuStream> imu,
                               const SequenceReaderOptions& options)
    : left_(std::move(left)), right_(std::move(right)), imu_(std::move(imu)), options_(options) {
  bool first = true;
  auto extend = [&](const StreamInfo& info) {
    if (info.count == 0 || (info.t_first_ns == 0 && info.t_last_ns == 0)) return;
    start_ns_ = first ? info.t_first_ns : std::min(start_ns_, info.t_first_ns);
    end_ns_ = first ? info.t_last_ns : std::max(end_ns_, info.t_last_ns);
    first = false;
  };
  extend(left_->info());
  extend(right_->info());
  if (imu_) extend(imu_->info());
  next_ns_ = start_ns_;
  period_ns_ = ((end_ns_ - start_ns_) / options_.packet_ns + 1) * options_.packet_ns;
}

Expected<bool> SequenceReader::Next(SensorPacket* packet) {
  packet->left.clear();
  packet->right.clear();
  packet->imu.clear();
  const bool ended = left_->AtEnd() && right_->AtEnd() && (!imu_ || imu_->AtEnd());
  if (ended) {
    if (pass_ + 1 >= options_.passes) return false;
    // The next pass: from the start again, its clock one period later.
    AAVIO_RETURN_IF_ERROR(Seek(start_ns_ + (pass_ + 1) * period_ns_));
  } else if (options_.passes > 1 && next_ns_ >= start_ns_ + period_ns_) {
    return FailedPrecondition("the sequence has data past the end its files state (" +
                              FormatSecondsNs(end_ns_) +
                              " s); it cannot be read in several passes");
  }
  const TimeNs shift_ns = pass_ * period_ns_;
  // Through a stretch without data the packets grow, doubling while under 1 s: a gap of hours
  // is read in thousands of packets, not millions, and a packet never holds 1 s of data or more.
  const TimeNs end_ns = next_ns_ + options_.packet_ns * empty_growth_;
  AAVIO_RETURN_IF_ERROR(left_->ReadUntil(end_ns, &packet->left));
  AAVIO_RETURN_IF_ERROR(right_->ReadUntil(end_ns, &packet->right));
  if (imu_) AAVIO_RETURN_IF_ERROR(imu_->ReadUntil(end_ns, &packet->imu));
  packet->t_begin_ns = next_ns_ + shift_ns;
  packet->t_end_ns = end_ns + shift_ns;
  if (shift_ns != 0) {
    for (auto* events : {&packet->left, &packet->right}) {
      for (events::Event& e : *events)
        e.t_ns += shift_ns;
    }
    for (imu::ImuSample& s : packet->imu)
      s.t_ns += shift_ns;
  }
  next_ns_ = end_ns;
  const bool empty = packet->left.empty() && packet->right.empty() && packet->imu.empty();
  if (!empty || options_.passes > 1) {
    empty_growth_ = 1;
  } else if (options_.packet_ns * empty_growth_ * 2 <= kNsPerS) {
    empty_growth_ *= 2;
  }
  return true;
}

Status SequenceReader::Seek(TimeNs t_ns) {
  // Which pass t_ns falls in, and where in it.
  pass_ = 0;
  if (options_.passes > 1 && t_ns >= start_ns_ + period_ns_) {
    pass_ =
        static_cast<int>(std::min<TimeNs>((t_ns - start_ns_) / period_ns_, options_.passes - 1));
    t_ns -= pass_ * period_ns_;
  }
  AAVIO_RETURN_IF_ERROR(left_->Seek(t_ns));
  AAVIO_RETURN_IF_ERROR(right_->Seek(t_ns));
  if (imu_) AAVIO_RETURN_IF_ERROR(imu_->Seek(t_ns));
  next_ns_ = t_ns;
  empty_growth_ = 1;
  return Status::Ok();
}

}  // namespace aavio::io
