// AEDAT 4.0 (iniVation DV): the header's stream XML, packet headers, LZ4 / Zstandard packets and
// the flatbuffers of event and IMU packets.
#include "aavio/io/formats/aedat4/aedat4.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const std::string path = fuzz::WriteInput("input.aedat4", data, size);
  const io::StreamOptions options = fuzz::FuzzStreamOptions();
  if (auto events = io::OpenAedat4EventStream(path, "", options)) fuzz::Drain(**events);
  if (auto imu = io::OpenAedat4ImuStream(path, "", options)) fuzz::Drain(**imu);
  return 0;
}
