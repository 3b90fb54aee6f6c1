#pragma once
/// Streams over a ROS1 bag (docs/io.md): events from an EventArray topic (dvs_msgs,
/// dv_ros_msgs or prophesee_event_msgs, recognised by md5), IMU samples from a sensor_msgs/Imu
/// topic, ground truth from a geometry_msgs/PoseStamped topic. Events come out in event time, not
/// bag time, whatever the packet sizes (one-event packets included). Only the chunks that hold
/// the topic are decompressed, one at a time.

#include <memory>
#include <string>
#include <vector>

#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/io/formats/rosbag/rosbag_file.hpp"
#include "aavio/io/streams.hpp"

namespace aavio::io {

/// Topic names; an empty imu / ground_truth topic means "the only topic of that type".
struct BagTopics {
  std::string left_events = "/davis/left/events";
  std::string right_events = "/davis/right/events";
  std::string imu;
  std::string ground_truth;
};

struct BagEventDecoder;  // the format's decoder (bag_streams.cpp)

class BagEventStream final : public DecodedStream<events::Event, BagEventDecoder> {
 public:
  static Expected<std::unique_ptr<BagEventStream>> Open(const std::string& path,
                                                        const std::string& topic,
                                                        const StreamOptions& options);
  ~BagEventStream() override;
  /// Number of EventArray messages on the topic (from the index).
  std::uint64_t message_count() const;

 private:
  using DecodedStream::DecodedStream;
};

struct BagImuDecoder;  // the format's decoder (bag_streams.cpp)

class BagImuStream final : public DecodedStream<imu::ImuSample, BagImuDecoder> {
 public:
  /// `topic` empty: the bag's only sensor_msgs/Imu topic.
  static Expected<std::unique_ptr<BagImuStream>> Open(const std::string& path,
                                                      const std::string& topic,
                                                      const StreamOptions& options);
  ~BagImuStream() override;

 private:
  using DecodedStream::DecodedStream;
};

/// All poses of a geometry_msgs/PoseStamped topic (empty: the only one), sorted by stamp.
Expected<std::vector<geometry::StampedPose>> ReadBagPoses(const std::string& path,
                                                          const std::string& topic);

/// "topic (type, N msgs)" for every connection: for messages about missing topics.
std::string DescribeBagTopics(const rosbag::BagFile& bag);

/// The topic of the only connection with the given md5, or an error listing the topics.
Expected<std::string> FindTopicByType(const rosbag::BagFile& bag, const char* md5,
                                      const char* type_name);

}  // namespace aavio::io
