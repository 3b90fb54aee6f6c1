#pragma once
// Random vectors whose coordinates are drawn in a fixed order.
//
// In `Eigen::Vector3d(d(rng), d(rng), d(rng))` the order of the three draws is the compiler's
// choice (function arguments are unsequenced): GCC draws z first, clang x first, so one seed gave
// one scene with one compiler and another scene with the other. Drawing one coordinate per
// statement fixes the order. It is z, y, x: the order the simulator's worlds and the tests' data
// were first generated in, so that a seed keeps giving what it always gave.

#include <Eigen/Core>

namespace aavio::geometry {

// Three draws of `dist`: z first, then y, then x.
template <class Distribution, class Engine>
Eigen::Vector3d DrawZyx(Distribution& dist, Engine& rng) {
  Eigen::Vector3d v;
  v.z() = dist(rng);
  v.y() = dist(rng);
  v.x() = dist(rng);
  return v;
}

// Two draws of `dist`: y first, then x.
template <class Distribution, class Engine>
Eigen::Vector2d DrawYx(Distribution& dist, Engine& rng) {
  Eigen::Vector2d v;
  v.y() = dist(rng);
  v.x() = dist(rng);
  return v;
}

}  // namespace aavio::geometry
