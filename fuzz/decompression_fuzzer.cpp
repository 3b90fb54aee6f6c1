// The LZ4 frame and Zstandard decoders of bag, MCAP and AEDAT4 chunks; the first byte picks the
// codec and whether the size is stated (as containers do) or grown.
#include "aavio/io/decompression.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::span<const unsigned char> in(data + 1, size - 1);
  const std::size_t expected_size = (mode & 2) ? std::size_t{mode} * 64 : 0;
  std::vector<unsigned char> out;
  if (mode & 1) {
    (void)io::DecompressZstd(in, expected_size, &out);
  } else {
    (void)io::DecompressLz4Frame(in, expected_size, &out);
  }
  return 0;
}
