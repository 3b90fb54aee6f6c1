#pragma once
/// One event of an event camera, as the sensor reports it.

#include <cstdint>

#include "aavio/common/time.hpp"

namespace aavio::events {

struct Event {
  TimeNs t_ns = 0;            ///< timestamp on the dataset's clock
  std::uint16_t x = 0;        ///< raw (distorted) pixel column
  std::uint16_t y = 0;        ///< raw pixel row
  std::uint8_t polarity = 0;  ///< 1 = ON (brighter), 0 = OFF

  friend bool operator==(const Event&, const Event&) = default;
};

}  // namespace aavio::events
