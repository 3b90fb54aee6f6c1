#include "aavio/recording/mapping_counts.hpp"

#include <utility>

namespace aavio::recording {

void MappingCounts::Add(const mapping::MappingCycleReport& r) {
  for (const auto& [name, value] :
       {std::pair{"static_candidates", r.static_candidates},
        std::pair{"temporal_candidates", r.temporal_candidates},
        std::pair{"static_matches", r.static_matches},
        std::pair{"temporal_matches", r.temporal_matches},
        std::pair{"static_points", r.static_points},
        std::pair{"temporal_points", r.temporal_points},
        std::pair{"temporal_no_segment", r.temporal.no_segment},
        std::pair{"temporal_no_match", r.temporal.no_match},
        std::pair{"temporal_ill_conditioned", r.temporal.ill_conditioned},
        std::pair{"temporal_check_rejected", r.temporal.check_rejected},
        std::pair{"temporal_out_of_range", r.temporal.out_of_range},
        std::pair{"cycles_with_partner", r.has_partner ? 1 : 0}}) {
    sums_[name] += value;
  }
}

nlohmann::json MappingCounts::PerCycleJson(std::int64_t cycles) const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, total] : sums_)
    j[name] = cycles > 0 ? total / static_cast<double>(cycles) : 0.0;
  return j;
}

}  // namespace aavio::recording
