#pragma once
/// summary.json `mapping_per_cycle`: a mapping cycle's candidates, matches and points of each
/// kind of stereo, the cycles with a temporal partner, and where temporal candidates were lost
/// (docs/mapping.md), averaged over a run's mapping cycles. `aavio run` writes it in every mode
/// that maps.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "aavio/mapping/mapper.hpp"

namespace aavio::recording {

class MappingCounts {
 public:
  /// One cycle's counts (bootstrap cycles have none to add).
  void Add(const mapping::MappingCycleReport& report);
  /// The sums divided by `cycles`, the run's mapping cycles (bootstraps included).
  nlohmann::json PerCycleJson(std::int64_t cycles) const;

 private:
  std::map<std::string, double> sums_;
};

}  // namespace aavio::recording
