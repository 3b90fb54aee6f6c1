#include "aavio/common/log_histogram.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace aavio {
namespace {

double ExactQuantile(std::vector<double> v, double q) {
  const auto k =
      std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

TEST(LogHistogram, QuantilesWithinHalfAPercentOfTheExactOnes) {
  std::mt19937_64 rng(3);
  std::lognormal_distribution<double> ms(0.5, 1.5);  // stage times: 0.01 ms … 1 s
  std::vector<double> values;
  LogHistogram h;
  for (int i = 0; i < 200000; ++i) {
    values.push_back(ms(rng));
    h.Add(values.back());
  }
  EXPECT_EQ(h.count(), values.size());
  for (const double q : {0.0, 0.05, 0.5, 0.95, 0.999}) {
    const double exact = ExactQuantile(values, q);
    EXPECT_NEAR(h.Quantile(q), exact, 0.005 * exact) << "q = " << q;
  }
}

TEST(LogHistogram, ZerosTinyAndHugeValues) {
  LogHistogram h;
  EXPECT_EQ(h.Quantile(0.5), 0.0);  // empty
  for (int i = 0; i < 6; ++i)
    h.Add(0.0);
  h.Add(1e-9);  // below the range: counted as 0
  h.Add(-1.0);
  h.Add(1e15);  // above: counted as 1e12
  h.Add(1e12);
  EXPECT_EQ(h.count(), 10u);
  EXPECT_EQ(h.Quantile(0.5), 0.0);
  EXPECT_NEAR(h.Quantile(0.9), 1e12, 0.005 * 1e12);
}

TEST(LogHistogram, TenMillionValues) {
  // Ten million values, a thousand distinct ones from 0 to 1e9.
  LogHistogram h;
  for (int i = 0; i < 10'000'000; ++i)
    h.Add(static_cast<double>(i % 1000) * 1e6);
  EXPECT_EQ(h.count(), 10'000'000u);
  EXPECT_NEAR(h.Quantile(0.5), 500e6, 0.005 * 500e6);
}

}  // namespace
}  // namespace aavio
