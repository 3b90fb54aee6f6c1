#pragma once

// Branch-free float logarithm and exponential that the compiler vectorises (std::log / std::exp
// are library calls it cannot). Pure arithmetic on IEEE-754 floats: the same input gives the same
// bits on every x86-64 / AArch64 build without -ffast-math, so results stay deterministic.

#include <algorithm>
#include <bit>
#include <cstdint>

namespace aavio {

/// Natural logarithm of a positive, finite, normal float; |error| < 2e-7 relative to std::log
/// (tested over [1e-30, 1e30]). Not for 0, negatives, subnormals, inf or NaN.
inline float FastLog(float x) {
  // x = m · 2^e with m in [√½, √2); log m = 2·atanh(s), s = (m − 1)/(m + 1), |s| ≤ 0.1716.
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  const std::uint32_t shifted = bits - 0x3f3504f3u;  // subtract the bits of √½
  const int e = static_cast<int>(shifted) >> 23;     // arithmetic shift: floor(log2(x / √½))
  const float m = std::bit_cast<float>(bits - (static_cast<std::uint32_t>(e) << 23));
  const float s = (m - 1.0f) / (m + 1.0f);
  const float s2 = s * s;
  const float series =
      2.0f + s2 * (0.6666666667f + s2 * (0.4f + s2 * (0.2857142857f + s2 * 0.2222222222f)));
  return static_cast<float>(e) * 0.6931471806f + s * series;
}

/// e^x for x in [-87, 0] (decays: time surfaces, weights); |error| < 3e-7 relative to std::exp.
/// Inputs below -87 give e^-87 (≈ 1.6e-38).
inline float FastExpNonPositive(float x) {
  x = std::max(x, -87.0f);
  // e^x = 2^k · e^r, k = round(x / ln 2), |r| ≤ ln2 / 2; e^r by a degree-6 Taylor polynomial.
  const float kf = static_cast<float>(static_cast<int>(x * 1.4426950409f - 0.5f));
  // Cody–Waite: ln 2 split so that kf · ln2_hi is exact and r keeps its accuracy.
  const float r = (x - kf * 0.693145751953125f) - kf * 1.428606765330187e-6f;
  const float p =
      1.0f +
      r * (1.0f +
           r * (0.5f + r * (0.1666666667f +
                            r * (0.04166666667f + r * (0.008333333333f + r * 0.001388888889f)))));
  const std::uint32_t scale = static_cast<std::uint32_t>(static_cast<int>(kf) + 127) << 23;
  return p * std::bit_cast<float>(scale);
}

}  // namespace aavio
