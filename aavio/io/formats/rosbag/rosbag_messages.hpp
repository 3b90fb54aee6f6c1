#pragma once
/// The ROS1 messages aavio reads and writes, serialized by hand (docs/io.md):
/// dvs_msgs/EventArray (also dv_ros_msgs and prophesee_event_msgs: same layout, same md5),
/// sensor_msgs/Imu and geometry_msgs/PoseStamped. Little-endian, no padding.

#include <span>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"
#include "aavio/events/event.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/imu/imu_sample.hpp"

namespace aavio::io::rosbag {

struct MessageType {
  const char* name;
  const char* md5sum;
  const char* definition;  ///< full text with dependencies, as rosbag stores it
};

extern const MessageType kEventArray;   ///< dvs_msgs/EventArray, md5 5e8beee5…
extern const MessageType kImu;          ///< sensor_msgs/Imu, md5 6a62c6da…
extern const MessageType kPoseStamped;  ///< geometry_msgs/PoseStamped, md5 d3812c3c…
/// The pre-2017 dvs_msgs/EventArray (events with a uint64 time), refused with a clear message.
inline constexpr const char* kLegacyEventArrayMd5 = "d2e726b2040dbc135644f4709c150a10";

struct EventArrayHeader {
  TimeNs stamp_ns = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

/// Appends the events of one serialized EventArray. Returns false if the bytes are malformed.
bool DecodeEventArray(std::span<const std::uint8_t> data, EventArrayHeader* header,
                      std::vector<events::Event>* out);
bool DecodeImu(std::span<const std::uint8_t> data, imu::ImuSample* out);
bool DecodePoseStamped(std::span<const std::uint8_t> data, geometry::StampedPose* out);

void EncodeEventArray(TimeNs stamp_ns, std::uint32_t seq, const std::string& frame_id,
                      std::uint32_t width, std::uint32_t height,
                      std::span<const events::Event> events, std::vector<std::uint8_t>* out);
void EncodeImu(const imu::ImuSample& sample, std::uint32_t seq, const std::string& frame_id,
               std::vector<std::uint8_t>* out);
void EncodePoseStamped(const geometry::StampedPose& pose, std::uint32_t seq,
                       const std::string& frame_id, std::vector<std::uint8_t>* out);

}  // namespace aavio::io::rosbag
