#pragma once
/// Writes ROS1 bags (v2.0, indexed, chunks uncompressed / lz4 / bz2) that the ROS tools and the
/// ESVO family read unchanged (docs/simulator.md): dvs_msgs/EventArray in fixed packets (1 ms by
/// default, stamped at the packet's end, as ESVO's repacking tools do), sensor_msgs/Imu and
/// geometry_msgs/PoseStamped. Bag time = header stamp.

#include <map>
#include <memory>
#include <span>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/events/event.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::io {

enum class BagCompression { kNone, kLz4, kBz2 };

struct BagWriterOptions {
  BagCompression compression = BagCompression::kLz4;
  std::size_t chunk_bytes = 768 * 1024;  ///< rosbag's default chunk threshold
  TimeNs event_packet_ns = kNsPerMs;     ///< EventArray packet length
  int width = 0;                         ///< sensor size written into each EventArray
  int height = 0;
};

class BagWriter {
 public:
  static Expected<std::unique_ptr<BagWriter>> Create(const std::string& path,
                                                     const BagWriterOptions& options);
  ~BagWriter();  ///< closes; errors at this point are lost, so call Close

  /// Adds events of one topic (time order per topic); they are cut into packets of
  /// event_packet_ns, [k·P, (k+1)·P) stamped (k+1)·P.
  Status WriteEvents(const std::string& topic, std::span<const events::Event> events);
  Status WriteImu(const std::string& topic, const imu::ImuSample& sample);
  Status WritePose(const std::string& topic, const geometry::StampedPose& pose);
  /// Flushes pending packets and chunks, writes the index and closes the file.
  Status Close();

 private:
  struct State;
  explicit BagWriter(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
};

}  // namespace aavio::io
