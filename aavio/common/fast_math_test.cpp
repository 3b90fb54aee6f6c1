#include "aavio/common/fast_math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace aavio {
namespace {

TEST(FastMath, LogMatchesStdLogAcrossTheRange) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> exponent(-30.0, 30.0);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const float x = static_cast<float>(std::pow(10.0, exponent(rng)));
    const double expected = std::log(static_cast<double>(x));
    const double error = std::abs(static_cast<double>(FastLog(x)) - expected);
    worst = std::max(worst, error / std::max(1.0, std::abs(expected)));
  }
  EXPECT_LT(worst, 2e-7);
  // Exact powers of two and the boundaries of the mantissa interval.
  EXPECT_FLOAT_EQ(FastLog(1.0f), 0.0f);
  EXPECT_NEAR(FastLog(0.70710677f), std::log(0.70710677f), 1e-7);
  EXPECT_NEAR(FastLog(1.4142135f), std::log(1.4142135f), 1e-7);
  EXPECT_NEAR(FastLog(1024.0f), std::log(1024.0f), 1e-6);
}

TEST(FastMath, ExpMatchesStdExpOnNonPositiveInputs) {
  double worst = 0.0;
  for (int i = 0; i <= 870000; ++i) {
    const float x = -static_cast<float>(i) * 1e-4f;
    const double expected = std::exp(static_cast<double>(x));
    worst =
        std::max(worst, std::abs(static_cast<double>(FastExpNonPositive(x)) - expected) / expected);
  }
  EXPECT_LT(worst, 3e-7);
  EXPECT_EQ(FastExpNonPositive(0.0f), 1.0f);
  EXPECT_GT(FastExpNonPositive(-1000.0f), 0.0f);
  EXPECT_LT(FastExpNonPositive(-1000.0f), 1e-37f);
}

}  // namespace
}  // namespace aavio
