#pragma once
/// Checks of numeric options. CLI11's Range and NonNegativeNumber let "nan" through (every
/// comparison with NaN is false); these refuse NaN and infinities as well.

#include <CLI/CLI.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "aavio/common/format.hpp"

namespace aavio::cli {

/// A finite number in [lo, hi].
inline CLI::Validator NumberIn(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) {
          return StrFormat("'%s' is not a number; give one in [%g, %g]", text.c_str(), lo, hi);
        }
        if (value < lo || value > hi)
          return StrFormat("Value %s not in range [%g, %g]", text.c_str(), lo, hi);
        return std::string();
      },
      StrFormat("NUMBER in [%g - %g]", lo, hi));
}

/// A finite number >= 0.
inline CLI::Validator NonNegative() {
  return NumberIn(0.0, std::numeric_limits<double>::max());
}

/// A seed: a whole number that fits 64 bits (a larger one would wrap to another seed).
inline CLI::Validator Seed() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.size() <= 20 &&
                            text.find_first_not_of("0123456789") == std::string::npos;
        // 20 digits fit only up to 18446744073709551615 (compared as text, same length).
        if (!digits || (text.size() == 20 && text > "18446744073709551615")) {
          return "Value " + text + " is not a seed: give a whole number from 0 to " +
                 "18446744073709551615";
        }
        return std::string();
      },
      "UINT64");
}

/// A span of data time in seconds: 0 to a million (11.6 days; larger ones overflow nanoseconds
/// on a sensor clock).
inline CLI::Validator DataSeconds() {
  return NumberIn(0.0, 1e6);
}

}  // namespace aavio::cli
