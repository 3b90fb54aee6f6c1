#pragma once
/// Quantiles of a long stream of non-negative values in bounded memory: values are counted in bins
/// 1 % wide (relative) from 1e-6 to 1e12, so a quantile comes back within 0.5 % of the exact one
/// however many values were added (values below 1e-6 count as 0, values above 1e12 as 1e12).
/// Per-stage timings use it: a day-long run adds millions of samples per stage.

#include <cstdint>
#include <vector>

namespace aavio {

class LogHistogram {
 public:
  void Add(double x);
  std::uint64_t count() const { return count_; }
  /// The value of rank ⌊q·count⌋ (0 ≤ q < 1) of the sorted values, to within 0.5 %; 0 when empty.
  double Quantile(double q) const;

 private:
  std::vector<std::uint64_t> bins_;  ///< bins_[0]: values below 1e-6; grown to the largest bin used
  std::uint64_t count_ = 0;
};

}  // namespace aavio
