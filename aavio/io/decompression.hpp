#pragma once
/// Whole-buffer decompression of the LZ4 frame format and of Zstandard frames, as containers use
/// them (ROS1 bag chunks, MCAP chunks, AEDAT4 packets). `expected_size` > 0: the container states
/// the decompressed size, which must match; 0: the output grows as needed. Errors name the cause;
/// the caller adds the file and the byte.

#include <cstddef>
#include <span>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio::io {

Status DecompressLz4Frame(std::span<const unsigned char> in, std::size_t expected_size,
                          std::vector<unsigned char>* out);
Status DecompressZstd(std::span<const unsigned char> in, std::size_t expected_size,
                      std::vector<unsigned char>* out);

}  // namespace aavio::io
