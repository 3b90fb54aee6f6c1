// The text readers, each on every input: events.txt (`t x y p`), imu.txt in the ECD and the
// TUM-VIE layouts, and TUM trajectories (`t x y z qx qy qz qw`).
#include "aavio/io/formats/text/text_streams.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const std::string path = fuzz::WriteInput("input.txt", data, size);
  io::StreamOptions options = fuzz::FuzzStreamOptions();
  options.width = 346;
  options.height = 260;
  if (auto events = io::TextEventStream::Open(path, options)) fuzz::Drain(**events);
  for (io::ImuTextLayout layout : {io::ImuTextLayout::kEcd, io::ImuTextLayout::kTumVie}) {
    if (auto imu = io::TextImuStream::Open(path, layout, options)) fuzz::Drain(**imu);
  }
  (void)io::ReadTumTrajectory(path);
  return 0;
}
