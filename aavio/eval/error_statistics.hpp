#pragma once
/// Summary statistics of a set of errors, the ones rpg_trajectory_evaluation writes per metric
/// (`compute_statistics`: rmse, mean, median, std, min, max, num_samples).

#include <cstddef>
#include <vector>

namespace aavio::eval {

struct ErrorStatistics {
  std::size_t samples = 0;
  double rmse = 0.0, mean = 0.0, median = 0.0, std = 0.0, min = 0.0, max = 0.0;
};

/// All zero for an empty set. std is the population standard deviation (numpy's default);
/// median of an even count is the mean of the two middle values (numpy.median).
ErrorStatistics ComputeStatistics(const std::vector<double>& errors);

}  // namespace aavio::eval
