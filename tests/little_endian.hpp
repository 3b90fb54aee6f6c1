#pragma once
// Byte-level fixtures: numbers appended least significant byte first, the byte order of every
// binary format aavio reads (Prophesee RAW, AEDAT 4.0, ROS 2 CDR and MCAP), to a byte buffer
// (std::string or a vector of char or unsigned char).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace aavio::testing {

/// Integers, and IEEE floats by their bits.
template <typename T, typename Buffer>
void AppendLittleEndian(Buffer* bytes, T value) {
  using Byte = typename Buffer::value_type;
  std::uint64_t bits = 0;
  if constexpr (std::is_same_v<T, float>) {
    bits = std::bit_cast<std::uint32_t>(value);
  } else if constexpr (std::is_same_v<T, double>) {
    bits = std::bit_cast<std::uint64_t>(value);
  } else {
    static_assert(std::is_integral_v<T> || std::is_enum_v<T>, "integers or floats");
    bits = static_cast<std::uint64_t>(value);
  }
  for (std::size_t k = 0; k < sizeof(T); ++k)
    bytes->push_back(static_cast<Byte>((bits >> (8 * k)) & 0xFF));
}

}  // namespace aavio::testing
