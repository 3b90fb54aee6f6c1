// Where mapping cycles run: inline in the tick; concurrently with the map handed over a cycle
// later (waited for); in real time handed over when done, a cycle due meanwhile skipped; a reset
// drops a cycle still running.
#include "aavio/pipeline/mapping_runner.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "aavio/mapping/mapping_test_utils.hpp"

namespace aavio::pipeline {
namespace {

constexpr TimeNs kCycleNs = 50 * kNsPerMs;

class MappingRunnerTest : public ::testing::Test {
 protected:
  MappingRunnerTest() : obs_(mapping::testing::PlaneObservation()) {
    config_.bootstrap.min_points = 100;
    config_.max_points = 5000;
  }
  std::unique_ptr<MappingRunner> Initialized(MappingRunner::Mode mode) {
    auto runner = std::make_unique<MappingRunner>(stereo_, valid_, config_, mode, kCycleNs);
    EXPECT_TRUE(runner->Initialize({obs_, {}}, true).ok());
    EXPECT_TRUE(runner->initialized());
    return runner;
  }
  mapping::PosedObservation At(TimeNs t_ns) const {
    auto next = std::make_shared<events::Observation>(*obs_);
    next->t_ns = t_ns;
    return {next, {}};
  }

  mapping::RectifiedStereo stereo_ = mapping::testing::SmallStereo();
  cv::Mat valid_ = cv::Mat(120, 160, CV_8UC1, cv::Scalar(255));
  mapping::MappingConfig config_;
  std::shared_ptr<events::Observation> obs_;
};

TEST_F(MappingRunnerTest, ModeFollowsThePipelineConfig) {
  PipelineConfig config;
  EXPECT_EQ(MappingRunner::ModeOf(config), MappingRunner::Mode::kConcurrent);
  config.concurrent_mapping = false;
  EXPECT_EQ(MappingRunner::ModeOf(config), MappingRunner::Mode::kInline);
  config.real_time = true;
  EXPECT_EQ(MappingRunner::ModeOf(config), MappingRunner::Mode::kRealTime);
}

TEST_F(MappingRunnerTest, InlineRunsTheCycleInTheTick) {
  std::unique_ptr<MappingRunner> runner = Initialized(MappingRunner::Mode::kInline);
  bool skipped = true;
  Expected<std::optional<MappingRunner::Cycle>> cycle =
      runner->Start(kCycleNs, At(kCycleNs), {}, &skipped);
  ASSERT_TRUE(cycle.ok()) << cycle.status().message();
  ASSERT_TRUE(cycle->has_value());
  EXPECT_FALSE(skipped);
  EXPECT_GT((*cycle)->report.static_points, 500);
  double waited_ms = -1.0;
  Expected<std::optional<MappingRunner::Cycle>> later = runner->Collect(2 * kCycleNs, &waited_ms);
  ASSERT_TRUE(later.ok());
  EXPECT_FALSE(later->has_value());
  EXPECT_EQ(waited_ms, 0.0);
}

TEST_F(MappingRunnerTest, ConcurrentHandsTheCycleOverOneCycleLater) {
  std::unique_ptr<MappingRunner> runner = Initialized(MappingRunner::Mode::kConcurrent);
  bool skipped = true;
  Expected<std::optional<MappingRunner::Cycle>> started =
      runner->Start(kCycleNs, At(kCycleNs), {}, &skipped);
  ASSERT_TRUE(started.ok());
  EXPECT_FALSE(started->has_value());  // running on its thread
  EXPECT_FALSE(skipped);
  double waited_ms = 0.0;
  // Not before the next cycle's tick, however long it has been done.
  Expected<std::optional<MappingRunner::Cycle>> early =
      runner->Collect(2 * kCycleNs - kNsPerMs, &waited_ms);
  ASSERT_TRUE(early.ok());
  EXPECT_FALSE(early->has_value());
  Expected<std::optional<MappingRunner::Cycle>> due = runner->Collect(2 * kCycleNs, &waited_ms);
  ASSERT_TRUE(due.ok());
  ASSERT_TRUE(due->has_value());
  EXPECT_GT((*due)->report.static_points, 500);
  EXPECT_GE(waited_ms, 0.0);
  // Handed over once.
  EXPECT_FALSE(runner->Collect(3 * kCycleNs, &waited_ms)->has_value());
}

TEST_F(MappingRunnerTest, RealTimeSkipsACycleDueWhileOneRuns) {
  std::unique_ptr<MappingRunner> runner = Initialized(MappingRunner::Mode::kRealTime);
  bool skipped = false;
  ASSERT_TRUE(runner->Start(kCycleNs, At(kCycleNs), {}, &skipped).ok());
  EXPECT_FALSE(skipped);
  // Due at once again, before the first can be collected: skipped.
  ASSERT_TRUE(runner->Start(kCycleNs + 1, At(kCycleNs + 1), {}, &skipped).ok());
  EXPECT_TRUE(skipped);
  // Handed over at the first tick after it is done (ticks go on until then).
  double waited_ms = 0.0;
  std::optional<MappingRunner::Cycle> cycle;
  // (Up to 10 s of wall time: a cycle that never finishes fails here rather than hangs.)
  TimeNs t = kCycleNs + 2;
  for (int polls = 0; !cycle && polls < 10000; ++polls, t += kNsPerMs) {
    Expected<std::optional<MappingRunner::Cycle>> collected = runner->Collect(t, &waited_ms);
    ASSERT_TRUE(collected.ok());
    cycle = std::move(*collected);
    if (!cycle) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(cycle.has_value()) << "the cycle was not handed over within 10 s";
  EXPECT_GT(cycle->report.static_points, 500);
}

TEST_F(MappingRunnerTest, ResetDropsACycleStillRunning) {
  std::unique_ptr<MappingRunner> runner = Initialized(MappingRunner::Mode::kConcurrent);
  bool skipped = false;
  ASSERT_TRUE(runner->Start(kCycleNs, At(kCycleNs), {}, &skipped).ok());
  runner->Reset();
  EXPECT_FALSE(runner->initialized());
  EXPECT_EQ(runner->local_map(), nullptr);
  double waited_ms = 0.0;
  EXPECT_FALSE(runner->Collect(2 * kCycleNs, &waited_ms)->has_value());
}

}  // namespace
}  // namespace aavio::pipeline
