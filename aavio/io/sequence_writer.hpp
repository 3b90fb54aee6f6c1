#pragma once
/// Writes a sequence folder (docs/cli.md) in one of the supported formats, streaming the events:
///   h5   events/{left,right}/events.h5 (DSEC layout), imu.txt, groundtruth.txt
///   txt  events/{left,right}/events.txt, imu.txt, groundtruth.txt
///   bag  events.bag (/davis/{left,right}/events, /davis/left/imu, /gt/pose) and groundtruth.txt
/// Close fills in the parts of a SequenceDescription it wrote; the caller adds calibration and
/// the rest and writes sequence.yaml.

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "aavio/io/formats/rosbag/bag_writer.hpp"
#include "aavio/io/sequence.hpp"

namespace aavio::io {

enum class SequenceFormat { kDsecH5, kBag, kText };

/// What a sequence folder written here holds, in any format (sequence.yaml included).
inline constexpr const char* kSequenceOutputs[] = {"sequence.yaml", "events", "events.bag",
                                                   "imu.txt", "groundtruth.txt"};
/// "h5", "bag" or "txt".
Expected<SequenceFormat> ParseSequenceFormat(const std::string& name);

struct SequenceWriterOptions {
  SequenceFormat format = SequenceFormat::kDsecH5;
  int width = 0;  ///< sensor size (written into bag EventArrays)
  int height = 0;
  BagCompression compression = BagCompression::kLz4;
};

class SequenceWriter {
 public:
  static Expected<std::unique_ptr<SequenceWriter>> Create(const std::string& folder,
                                                          const SequenceWriterOptions& options);
  ~SequenceWriter();

  /// Events of one camera, in time order.
  Status WriteEvents(bool left, std::span<const events::Event> events);
  /// IMU samples in time order (streamed into a bag; kept for imu.txt otherwise, ~50 B each).
  Status WriteImu(std::span<const imu::ImuSample> samples);
  /// Ground-truth poses (groundtruth.txt, and the /gt/pose topic of a bag).
  Status WritePoses(const std::vector<geometry::StampedPose>& poses);
  /// Finishes every file and records them in `d` (events, IMU and ground truth if written).
  Status Close(SequenceDescription* d);

 private:
  struct State;
  explicit SequenceWriter(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
};

}  // namespace aavio::io
