#include "aavio/common/log_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace aavio {
namespace {

constexpr double kSmallest = 1e-6, kLargest = 1e12;
const double kLogWidth = std::log1p(0.01);  // bins 1 % wide

// Bin k ≥ 1 holds [kSmallest·1.01^(k−1), kSmallest·1.01^k).
std::size_t BinOf(double x) {
  if (!(x >= kSmallest)) return 0;  // also NaN
  x = std::min(x, kLargest);
  return 1 + static_cast<std::size_t>(std::log(x / kSmallest) / kLogWidth);
}

double CentreOf(std::size_t bin) {
  if (bin == 0) return 0.0;
  return kSmallest * std::exp((static_cast<double>(bin) - 0.5) * kLogWidth);
}

}  // namespace

void LogHistogram::Add(double x) {
  const std::size_t bin = BinOf(x);
  if (bin >= bins_.size()) bins_.resize(bin + 1, 0);
  ++bins_[bin];
  ++count_;
}

double LogHistogram::Quantile(double q) const {
  if (count_ == 0) return 0.0;
  const auto rank =
      std::min(count_ - 1, static_cast<std::uint64_t>(q * static_cast<double>(count_)));
  std::uint64_t below = 0;
  for (std::size_t bin = 0; bin < bins_.size(); ++bin) {
    below += bins_[bin];
    if (below > rank) return CentreOf(bin);
  }
  return CentreOf(bins_.size() - 1);
}

}  // namespace aavio
