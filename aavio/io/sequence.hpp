#pragma once
/// A sequence = left and right event sources, an optional IMU, a calibration and optional ground
/// truth (docs/cli.md). It is described by a `sequence.yaml`:
///
///   name: box2_twin
///   calibration: calibration            # ESVO folder, left.yaml, or DSEC cam_to_cam.yaml
///   events:
///     left: events/left/events.h5       # .h5 | .bag | .txt | .raw | .db3 / .mcap | .aedat4
///     right: events/right/events.h5
///     left_topic: /davis/left/events    # bags (the defaults); .aedat4: stream id or name
///     right_topic: /davis/right/events
///   imu:                                # optional
///     path: imu.txt                     # .txt (layout: ecd | tum_vie), .bag (topic) or .aedat4
///     topic: /davis/left/imu            # bags; empty = the only sensor_msgs/Imu topic
///     layout: ecd
///   ground_truth:                       # optional
///     trajectory: groundtruth.txt       # TUM or EuRoC text, or a bag with a PoseStamped topic
///     topic: /gt/pose
///     depth: depth                      # folder of 16-bit disparity PNGs
///     calibration: calibration_true     # the true calibration (a simulated twin's)
///
/// Relative paths resolve against the folder of the sequence.yaml. Besides sequence.yaml,
/// DescribeSequence accepts a DSEC sequence folder (events/{left,right}/events.h5 +
/// calibration/cam_to_cam.yaml) and a bag file (with a calibration given separately).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/io/formats/rosbag/bag_streams.hpp"
#include "aavio/io/formats/text/text_streams.hpp"
#include "aavio/io/streams.hpp"

namespace aavio::io {

enum class SourceFormat { kDsecH5, kBag, kText, kPropheseeRaw, kRos2Bag, kAedat4 };
const char* SourceFormatName(SourceFormat format);
/// From the file name: .h5/.hdf5 DSEC layout, .bag, .txt, .raw (Prophesee), .db3 / .mcap (ROS 2
/// bags), .aedat4 (iniVation DV); otherwise an error.
Expected<SourceFormat> DetectSourceFormat(const std::string& path);

struct SourceSpec {
  SourceFormat format = SourceFormat::kDsecH5;
  std::string path;                                ///< absolute, or relative to the working folder
  std::string topic;                               ///< bags; .aedat4: the stream (id or name)
  ImuTextLayout imu_layout = ImuTextLayout::kEcd;  ///< IMU text files
};

struct SequenceDescription {
  std::string name;
  std::string origin;       ///< the file or folder it was read from
  std::string calibration;  ///< path for LoadCalibration; empty if none was given
  SourceSpec left;
  SourceSpec right;
  std::optional<SourceSpec> imu;
  std::optional<SourceSpec> gt_trajectory;  ///< text (TUM, EuRoC) or bag (PoseStamped topic)
  std::string gt_depth;
  std::string gt_calibration;  ///< the rig's true calibration, for LoadCalibration; may be empty
};

Expected<SequenceDescription> ReadSequenceYaml(const std::string& path);
/// Writes `description` as sequence.yaml at `path`; paths are written relative to its folder when
/// they lie inside it.
Status WriteSequenceYaml(const std::string& path, const SequenceDescription& description);

/// A sequence.yaml (or a folder holding one), a DSEC sequence folder or a bag. `calibration`
/// (if not empty) replaces the one the description names.
Expected<SequenceDescription> DescribeSequence(const std::string& path,
                                               const std::string& calibration = "");

Expected<std::unique_ptr<EventStream>> OpenEventStream(const SourceSpec& spec,
                                                       const StreamOptions& options);
Expected<std::unique_ptr<ImuStream>> OpenImuStream(const SourceSpec& spec,
                                                   const StreamOptions& options);
/// The poses of a ground-truth source: a TUM or EuRoC text file (told apart from the data), or a
/// bag's geometry_msgs/PoseStamped topic (empty: the only one).
Expected<std::vector<geometry::StampedPose>> ReadGroundTruthPoses(const SourceSpec& spec);
/// "path" or "path (topic T)", for messages.
std::string DescribeSource(const SourceSpec& spec);

/// Everything of every stream within [t_begin_ns, t_end_ns).
struct SensorPacket {
  TimeNs t_begin_ns = 0;
  TimeNs t_end_ns = 0;
  std::vector<events::Event> left;
  std::vector<events::Event> right;
  std::vector<imu::ImuSample> imu;
};

struct SequenceReaderOptions {
  TimeNs packet_ns =
      kNsPerMs;  ///< length of each packet (after one without data, doubling while under 1 s)
  StreamOptions stream;  ///< reorder window, sensor size, block size
  /// Read the sequence this many times back to back, each pass's clock shifted to follow the
  /// last (a long run from a short sequence: memory and speed over time). The camera jumps back
  /// to its start at each seam.
  int passes = 1;
};

/// Streams of one recording share a clock: the two cameras' time spans must overlap, and the
/// IMU's must overlap the events'. A stream whose span is unknown without reading it is not
/// checked.
Status CheckStreamsOverlap(const SequenceDescription& d, const StreamInfo& left,
                           const StreamInfo& right, const StreamInfo* imu);

/// What makes the IMU stream a sequence names useless to the tracker, from the samples read
/// (`samples` of them from `first_ns` to `last_ns`): none, or fewer than one per tick
/// (`tick_rate_hz`). Empty when it is fine, or when the sequence has no IMU.
std::string ImuStreamWarning(const SequenceDescription& d, std::int64_t samples, TimeNs first_ns,
                             TimeNs last_ns, double tick_rate_hz);

/// Merges the streams of a sequence into consecutive packets of data time.
class SequenceReader {
 public:
  static Expected<std::unique_ptr<SequenceReader>> Open(const SequenceDescription& description,
                                                        const SequenceReaderOptions& options);
  SequenceReader(std::unique_ptr<EventStream> left, std::unique_ptr<EventStream> right,
                 std::unique_ptr<ImuStream> imu, const SequenceReaderOptions& options);

  /// Fills the next packet; returns false (and leaves it empty) once every stream has ended.
  Expected<bool> Next(SensorPacket* packet);
  /// The next packet starts at t_ns.
  Status Seek(TimeNs t_ns);

  TimeNs start_ns() const { return start_ns_; }  ///< earliest stamp of any stream
  /// Latest stamp of any stream (as known), in the last pass.
  TimeNs end_ns() const { return end_ns_ + (options_.passes - 1) * period_ns_; }
  const EventStream& left() const { return *left_; }
  const EventStream& right() const { return *right_; }
  const ImuStream* imu() const { return imu_.get(); }

 private:
  std::unique_ptr<EventStream> left_, right_;
  std::unique_ptr<ImuStream> imu_;
  SequenceReaderOptions options_;
  TimeNs start_ns_ = 0;
  TimeNs end_ns_ = 0;
  TimeNs next_ns_ = 0;       // in the streams' own clock
  TimeNs empty_growth_ = 1;  // the next packet is this many packet_ns long (after empty ones)
  TimeNs period_ns_ = 0;     // one pass, a whole number of packets
  int pass_ = 0;
};

}  // namespace aavio::io
