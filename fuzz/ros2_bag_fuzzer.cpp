// ROS 2 bags: MCAP files (records, chunks, compression) and sqlite3 .db3 files, and the CDR event
// packets (event_camera_msgs) in either.
#include <cstring>

#include "aavio/io/formats/ros2_bag/ros2_bag.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const bool mcap = size >= 5 && std::memcmp(data, "\x89MCAP", 5) == 0;
  const std::string path = fuzz::WriteInput(mcap ? "input.mcap" : "input.db3", data, size);
  (void)io::ListRos2EventTopics(path);
  if (auto events = io::Ros2BagEventStream::Open(path, "", fuzz::FuzzStreamOptions())) {
    fuzz::Drain(**events);
  }
  return 0;
}
