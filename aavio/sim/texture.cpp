#include "aavio/sim/texture.hpp"

#include <algorithm>
#include <cmath>

namespace aavio::sim {

namespace {

/// A well-mixed 64-bit hash (splitmix64) of a cell and the seed, mapped to [0, 1).
double Hash01(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  std::uint64_t x = seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull) ^
                    (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full);
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) * (1.0 / 9007199254740992.0);
}

/// Coverage of "inside" (d > 0) for a step edge at signed distance d, box filter of width w.
double Coverage(double d, double w) {
  return std::clamp(0.5 + d / w, 0.0, 1.0);
}

double Mix(double a, double b, double t) {
  return a + (b - a) * t;
}

}  // namespace

void Texture::Prepare() {
  cos_ = std::cos(angle_rad);
  sin_ = std::sin(angle_rad);
  prepared_angle_ = angle_rad;
}

double Texture::Albedo(double u_m, double v_m, double footprint_m) const {
  const bool prepared = prepared_angle_ == angle_rad;
  const double c = prepared ? cos_ : std::cos(angle_rad);
  const double s = prepared ? sin_ : std::sin(angle_rad);
  const double x = (c * u_m + s * v_m) / cell_m;  // pattern coordinates, in cells
  const double y = (-s * u_m + c * v_m) / cell_m;
  const double w = std::max(footprint_m / cell_m, 1e-4);
  auto albedo = [&](double h) { return std::clamp(mean + contrast * (h - 0.5), 0.05, 1.0); };

  switch (pattern) {
    case Pattern::kBricks: {
      // Bricks 2 cells wide, 1 high, rows offset by half a brick; mortar 0.12 cells.
      const double row = std::floor(y);
      const double shifted = x / 2.0 + (static_cast<std::int64_t>(row) & 1 ? 0.5 : 0.0);
      const double col = std::floor(shifted);
      const double fy = y - row, fx = (shifted - col) * 2.0;
      const double mortar = 0.06;
      const double d = std::min({fy - mortar, 1.0 - mortar - fy, fx - mortar, 2.0 - mortar - fx});
      const double brick =
          albedo(Hash01(static_cast<std::int64_t>(col), static_cast<std::int64_t>(row), seed));
      return Mix(albedo(0.1), brick, Coverage(d, w));
    }
    case Pattern::kTiles: {
      const double i = std::floor(x), j = std::floor(y);
      const double fx = x - i, fy = y - j;
      const auto ii = static_cast<std::int64_t>(i), jj = static_cast<std::int64_t>(j);
      double value = albedo(Hash01(ii, jj, seed));
      // Neighbouring tiles matter only where the footprint reaches across an edge.
      const double dx = std::min(fx, 1.0 - fx), dy = std::min(fy, 1.0 - fy);
      if (dx < 0.5 * w) {
        const double other = albedo(Hash01(ii + (fx < 0.5 ? -1 : 1), jj, seed));
        value = Mix(other, value, Coverage(dx, w));
      }
      if (dy < 0.5 * w) {
        const double other = albedo(Hash01(ii, jj + (fy < 0.5 ? -1 : 1), seed));
        value = Mix(other, value, Coverage(dy, w));
      }
      return value;
    }
    case Pattern::kStripes: {
      const double j = std::floor(y);
      const double fy = y - j;
      const double self = albedo(Hash01(0, static_cast<std::int64_t>(j), seed));
      const double d = std::min(fy, 1.0 - fy);
      if (d >= 0.5 * w) return self;
      const double other =
          albedo(Hash01(0, static_cast<std::int64_t>(j) + (fy < 0.5 ? -1 : 1), seed));
      return Mix(other, self, Coverage(d, w));
    }
    case Pattern::kBlobs: {
      // One disc per cell, jittered centre and radius; the nearest cells are checked.
      double value = albedo(0.5);
      const std::int64_t ci = static_cast<std::int64_t>(std::floor(x));
      const std::int64_t cj = static_cast<std::int64_t>(std::floor(y));
      for (std::int64_t i = ci - 1; i <= ci + 1; ++i) {
        for (std::int64_t j = cj - 1; j <= cj + 1; ++j) {
          const double cx = static_cast<double>(i) + 0.2 + 0.6 * Hash01(i, j, seed + 1);
          const double cy = static_cast<double>(j) + 0.2 + 0.6 * Hash01(i, j, seed + 2);
          const double r = 0.15 + 0.3 * Hash01(i, j, seed + 3);
          const double d = r - std::hypot(x - cx, y - cy);
          if (d > -w) value = Mix(value, albedo(Hash01(i, j, seed + 4)), Coverage(d, w));
        }
      }
      return value;
    }
    case Pattern::kWindows: {
      // Facade bays of 1.5 × 1 cells: a window (dark or bright) with a light sill below it.
      const double bx = x / 1.5, by = y;
      const double i = std::floor(bx), j = std::floor(by);
      const double fx = (bx - i) * 1.5, fy = by - j;
      const double wall = albedo(Hash01(0, 0, seed));
      const double window =
          albedo(Hash01(static_cast<std::int64_t>(i), static_cast<std::int64_t>(j), seed) * 0.5);
      const double d_window = std::min({fx - 0.35, 1.15 - fx, fy - 0.3, 0.85 - fy});
      const double d_sill = std::min({fx - 0.28, 1.22 - fx, fy - 0.22, 0.3 - fy});
      double value = Mix(wall, albedo(0.95), Coverage(d_sill, w));
      return Mix(value, window, Coverage(d_window, w));
    }
  }
  return mean;
}

}  // namespace aavio::sim
