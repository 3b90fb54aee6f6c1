#pragma once
/// Time in aavio: int64 nanoseconds (`t_ns`) everywhere in the core. Dataset clocks are large
/// (UNIX seconds ~1.5e9, DSEC µs clock ~3.6e10), so doubles are used only at the edges, and text
/// timestamps are parsed and printed exactly, digit by digit, never through a double.

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

#include "aavio/common/status.hpp"

namespace aavio {

/// Nanoseconds on the dataset's clock.
using TimeNs = std::int64_t;

inline constexpr TimeNs kNsPerUs = 1'000;
inline constexpr TimeNs kNsPerMs = 1'000'000;
inline constexpr TimeNs kNsPerS = 1'000'000'000;

constexpr double NsToSeconds(TimeNs t_ns) {
  return static_cast<double>(t_ns) * 1e-9;
}
constexpr double NsToMs(TimeNs t_ns) {
  return static_cast<double>(t_ns) * 1e-6;
}
constexpr TimeNs UsToNs(std::int64_t t_us) {
  return t_us * kNsPerUs;
}
constexpr TimeNs MsToNs(double t_ms) {
  return static_cast<TimeNs>(t_ms * 1e6 + (t_ms >= 0 ? 0.5 : -0.5));
}
/// (t_us + offset_us) · 1000 into *t_ns; false if it does not fit TimeNs (±292 years): a
/// corrupt time in a file.
constexpr bool MicrosecondsToNs(std::int64_t t_us, std::int64_t offset_us, TimeNs* t_ns) {
  std::int64_t sum = 0;
  return !__builtin_add_overflow(t_us, offset_us, &sum) &&
         !__builtin_mul_overflow(sum, kNsPerUs, t_ns);
}

/// a + b, clamped to TimeNs's range (reads "until the end of time" add windows to INT64_MAX).
constexpr TimeNs SaturatingAdd(TimeNs a, TimeNs b) {
  TimeNs sum = 0;
  if (!__builtin_add_overflow(a, b, &sum)) return sum;
  return b > 0 ? std::numeric_limits<TimeNs>::max() : std::numeric_limits<TimeNs>::min();
}

/// Rounds to the nearest nanosecond. Exact only while |t| < ~9e6 s (a double's 53 bits); for
/// absolute dataset stamps parse text with ParseSecondsToNs instead.
constexpr TimeNs SecondsToNs(double t_s) {
  return static_cast<TimeNs>(t_s * 1e9 + (t_s >= 0 ? 0.5 : -0.5));
}

/// Parses a decimal number of seconds ("1468940145.123456789", "-0.5", "12", "3.6e4") into
/// nanoseconds. Plain decimals are converted exactly (digits past the 9th decimal are rounded
/// half up); exponent notation falls back to double arithmetic.
Expected<TimeNs> ParseSecondsToNs(std::string_view text);

/// Formats nanoseconds as seconds with exactly 9 decimals ("36470.774788442"), exactly.
std::string FormatSecondsNs(TimeNs t_ns);

}  // namespace aavio
