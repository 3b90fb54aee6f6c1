#pragma once
/// ROS 2 bags (rosbag2) with sqlite3 or MCAP storage — a `.db3` or `.mcap` file, or the bag's
/// folder (its storage files in name order) — holding `event_camera_msgs/msg/EventPacket` messages,
/// the packets the ros-event-camera drivers publish (metavision_driver, libcaer_driver), CDR
/// little-endian:
///   header (stamp, frame_id), uint32 height, uint32 width, uint64 seq, uint64 time_base,
///   string encoding, bool is_bigendian, uint8[] events.
/// Encodings `evt3` (the sensor's clock, unwrapped across packets), `libcaer` and `libcaer_cmp`
/// (host time: time_base + the sensor's µs) are decoded (event_codecs.hpp); others are refused
/// by name.
/// The bag is read once when opened (count, time range, sensor size; every packet checked), then
/// streamed packet by packet.

#include <memory>
#include <string>
#include <vector>

#include "aavio/io/streams.hpp"

namespace aavio::io {

struct Ros2EventTopic {
  std::string name;
  std::string encoding;  ///< of its first packet
  std::int64_t messages = 0;
};

/// The EventPacket topics of a ROS 2 bag.
Expected<std::vector<Ros2EventTopic>> ListRos2EventTopics(const std::string& path);

struct Ros2BagEventDecoder;  // the format's decoder (ros2_bag.cpp)

class Ros2BagEventStream final : public DecodedStream<events::Event, Ros2BagEventDecoder> {
 public:
  /// `topic` empty: the bag's only EventPacket topic.
  static Expected<std::unique_ptr<Ros2BagEventStream>> Open(const std::string& path,
                                                            const std::string& topic,
                                                            const StreamOptions& options);
  ~Ros2BagEventStream() override;

 private:
  using DecodedStream::DecodedStream;
};

}  // namespace aavio::io
