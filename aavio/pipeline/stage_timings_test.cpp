#include "aavio/pipeline/stage_timings.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aavio::pipeline {
namespace {

TEST(StageTimings, SummarisesEachStage) {
  StageTimings timings;
  for (int i = 1; i <= 100; ++i) {
    timings.Add("matching", static_cast<double>(i), 2000.0 + i);
    if (i % 10 == 0) timings.Add("fusion", 5.0);
  }
  const std::map<std::string, StageSummary> s = timings.Summary();
  ASSERT_EQ(s.size(), 2u);
  const StageSummary& m = s.at("matching");
  EXPECT_EQ(m.calls, 100u);
  EXPECT_NEAR(m.median_ms, 51.0, 0.005 * 51.0);  // rank ⌊0.5·100⌋ of 1…100
  EXPECT_NEAR(m.p95_ms, 96.0, 0.005 * 96.0);
  EXPECT_NEAR(m.median_items, 2051.0, 0.005 * 2051.0);
  EXPECT_EQ(m.median_items, std::round(m.median_items));
  EXPECT_DOUBLE_EQ(m.total_s, 5.050);  // exact: 5050 ms
  EXPECT_EQ(s.at("fusion").calls, 10u);
  EXPECT_NEAR(s.at("fusion").median_ms, 5.0, 0.025);
  EXPECT_EQ(s.at("fusion").median_items, 0.0);
}

}  // namespace
}  // namespace aavio::pipeline
