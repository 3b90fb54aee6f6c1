#include "aavio/pipeline/stage_timings.hpp"

#include <cmath>

namespace aavio::pipeline {

void StageTimings::Add(const std::string& stage, double ms, double items) {
  Samples& s = stages_[stage];
  s.ms.Add(ms);
  s.items.Add(items);
  s.total_ms += ms;
}

std::map<std::string, StageSummary> StageTimings::Summary() const {
  std::map<std::string, StageSummary> out;
  for (const auto& [name, s] : stages_) {
    out[name] = {s.ms.Quantile(0.5), s.ms.Quantile(0.95), static_cast<std::size_t>(s.ms.count()),
                 std::round(s.items.Quantile(0.5)), s.total_ms / 1000.0};
  }
  return out;
}

}  // namespace aavio::pipeline
