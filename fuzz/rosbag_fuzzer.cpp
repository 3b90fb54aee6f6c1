// ROS1 bags (format 2.0): records, the index, chunks stored plain, bz2 or lz4; the event
// (dvs / dv_ros / prophesee EventArray), IMU and PoseStamped messages in them.
#include "aavio/io/formats/rosbag/bag_streams.hpp"
#include "aavio/io/formats/rosbag/rosbag_file.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const std::string path = fuzz::WriteInput("input.bag", data, size);
  if (auto bag = io::rosbag::BagFile::Open(path)) (void)io::DescribeBagTopics(**bag);
  const io::StreamOptions options = fuzz::FuzzStreamOptions();
  if (auto events = io::BagEventStream::Open(path, "/davis/left/events", options)) {
    fuzz::Drain(**events);
  }
  if (auto imu = io::BagImuStream::Open(path, "", options)) fuzz::Drain(**imu);
  (void)io::ReadBagPoses(path, "");
  return 0;
}
