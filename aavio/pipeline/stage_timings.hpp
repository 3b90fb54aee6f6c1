#pragma once
/// Per-stage wall times of a run, summarised as summary.json reports them (docs/cli.md):
/// median and 95th percentile in ms, number of calls, median number of items per call, and the
/// total (where the wall time of a run went). Memory stays bounded however long the run: the
/// quantiles come from log histograms, within 0.5 % of the exact ones.

#include <cstddef>
#include <map>
#include <string>

#include "aavio/common/log_histogram.hpp"

namespace aavio::pipeline {

struct StageSummary {
  double median_ms = 0.0, p95_ms = 0.0;
  std::size_t calls = 0;
  double median_items = 0.0;  ///< rounded to a whole number
  double total_s = 0.0;
};

class StageTimings {
 public:
  void Add(const std::string& stage, double ms, double items = 0.0);
  /// Stages in name order.
  std::map<std::string, StageSummary> Summary() const;

 private:
  struct Samples {
    LogHistogram ms, items;
    double total_ms = 0.0;
  };
  std::map<std::string, Samples> stages_;
};

}  // namespace aavio::pipeline
