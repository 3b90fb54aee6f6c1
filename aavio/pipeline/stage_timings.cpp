#include "aavio/pipeline/stage_timings.hpp"

#include <algorithm>

namespace aavio::pipeline {
namespace {
double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const std::size_t k =
      std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}
}  // namespace

void StageTimings::Add(const std::string& stage, double ms, double items) {
  Samples& s = stages_[stage];
  s.ms.push_back(ms);
  s.items.push_back(items);
}

std::map<std::string, StageSummary> StageTimings::Summary() const {
  std::map<std::string, StageSummary> out;
  for (const auto& [name, s] : stages_) {
    double total_ms = 0.0;
    for (const double ms : s.ms)
      total_ms += ms;
    out[name] = {Quantile(s.ms, 0.5), Quantile(s.ms, 0.95), s.ms.size(), Quantile(s.items, 0.5),
                 total_ms / 1000.0};
  }
  return out;
}

}  // namespace aavio::pipeline
