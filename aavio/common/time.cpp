#include "aavio/common/time.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

namespace aavio {

Expected<TimeNs> ParseSecondsToNs(std::string_view text) {
  const std::string_view original = text;
  auto bad = [&](const char* why) {
    return ParseError("'" + std::string(original) + "' is not a time in seconds (" + why + ")");
  };
  if (text.empty()) return bad("empty");
  if (text.find_first_of("eE") != std::string_view::npos) {
    double value = 0.0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value)) {
      return bad("malformed number");
    }
    if (std::abs(value) > 9.2e9) return bad("out of range");
    return SecondsToNs(value);
  }
  bool negative = false;
  if (text.front() == '-' || text.front() == '+') {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  const size_t dot = text.find('.');
  const std::string_view int_part = text.substr(0, dot);
  const std::string_view frac_part =
      dot == std::string_view::npos ? std::string_view() : text.substr(dot + 1);
  if (int_part.empty() && frac_part.empty()) return bad("no digits");
  std::int64_t seconds = 0;
  for (char c : int_part) {
    if (c < '0' || c > '9') return bad("unexpected character");
    if (seconds > (std::numeric_limits<std::int64_t>::max() / kNsPerS) / 10) {
      return bad("out of range");
    }
    seconds = seconds * 10 + (c - '0');
  }
  std::int64_t frac_ns = 0;
  int digits = 0;
  bool round_up = false;
  for (char c : frac_part) {
    if (c < '0' || c > '9') return bad("unexpected character");
    if (digits < 9) {
      frac_ns = frac_ns * 10 + (c - '0');
    } else if (digits == 9) {
      round_up = c >= '5';
    }
    ++digits;
  }
  for (int i = digits; i < 9; ++i)
    frac_ns *= 10;
  TimeNs t_ns = seconds * kNsPerS + frac_ns + (round_up ? 1 : 0);
  return negative ? -t_ns : t_ns;
}

std::string FormatSecondsNs(TimeNs t_ns) {
  const bool negative = t_ns < 0;
  // Work in unsigned to handle INT64_MIN.
  const auto magnitude =
      negative ? static_cast<std::uint64_t>(-(t_ns + 1)) + 1u : static_cast<std::uint64_t>(t_ns);
  char buffer[48];
  std::snprintf(buffer, sizeof(buffer), "%s%llu.%09llu", negative ? "-" : "",
                static_cast<unsigned long long>(magnitude / kNsPerS),
                static_cast<unsigned long long>(magnitude % kNsPerS));
  return buffer;
}

}  // namespace aavio
