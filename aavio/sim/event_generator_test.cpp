#include "aavio/sim/event_generator.hpp"

#include <gtest/gtest.h>

#include <random>

namespace aavio::sim {
namespace {

EventCameraConfig Ideal() {
  EventCameraConfig c;
  c.threshold_sigma = 0.0;
  c.refractory_us = 0.0;
  c.noise_rate_hz = 0.0;
  return c;
}

TEST(EventGenerator, CrossingTimesAreInterpolatedLinearly) {
  EventGenerator gen(1, 1, Ideal(), 1);
  const float eps = static_cast<float>(Ideal().log_eps);
  gen.Reset({std::exp(-1.0f) - eps}, 0);  // log intensity −1
  std::vector<events::Event> out;
  gen.Step({std::exp(0.0f) - eps}, kNsPerMs, &out);  // to 0 over 1 ms: +1 = 4 × 0.25
  ASSERT_EQ(out.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(out[k].polarity, 1);
    EXPECT_NEAR(static_cast<double>(out[k].t_ns), (k + 1) * 250'000.0, 2.0);
  }
  out.clear();
  gen.Step({std::exp(-0.6f) - eps}, 2 * kNsPerMs, &out);  // down 0.6: two OFF events
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].polarity, 0);
  EXPECT_NEAR(static_cast<double>(out[0].t_ns), kNsPerMs + 0.25 / 0.6 * kNsPerMs, 2.0);
}

// Per pixel, the sum of polarities × threshold tracks the log-intensity change within one
// threshold (the first simulator invariant), with per-pixel threshold spread.
TEST(EventGenerator, PolaritySumTracksLogIntensity) {
  const int w = 16, h = 8;
  EventCameraConfig config = Ideal();
  config.threshold_sigma = 0.05;
  EventGenerator gen(w, h, config, 7);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> intensity(0.05f, 1.0f);
  std::vector<float> frame(w * h);
  for (float& v : frame)
    v = intensity(rng);
  const std::vector<float> first = frame;
  gen.Reset(frame, 0);
  std::vector<events::Event> events;
  for (int k = 1; k <= 200; ++k) {
    for (float& v : frame)
      v = std::clamp(v * std::exp(std::normal_distribution<float>(0, 0.2f)(rng)), 0.01f, 1.0f);
    gen.Step(frame, k * kNsPerMs, &events);
  }
  std::vector<int> on(w * h, 0), off(w * h, 0);
  for (const events::Event& e : events)
    (e.polarity ? on : off)[e.y * w + e.x]++;
  // Recover each pixel's thresholds from the generator's construction: same seed, same draws.
  std::mt19937_64 draws(7);
  std::normal_distribution<double> spread(0.0, config.threshold_sigma);
  for (int i = 0; i < w * h; ++i) {
    const double c_on = std::max(config.threshold_on + spread(draws), 0.2 * config.threshold_on);
    const double c_off = std::max(config.threshold_off + spread(draws), 0.2 * config.threshold_off);
    const float eps = static_cast<float>(config.log_eps);  // the generator works in float
    const double change = static_cast<double>(std::log(frame[i] + eps) - std::log(first[i] + eps));
    const double tracked = on[i] * c_on - off[i] * c_off;
    EXPECT_LT(std::abs(change - tracked), std::max(c_on, c_off) + 1e-5) << i;
  }
}

TEST(EventGenerator, StaticSceneGivesOnlyNoiseAtTheConfiguredRate) {
  EventCameraConfig config;
  config.noise_rate_hz = 2.0;
  const int w = 64, h = 48;
  EventGenerator gen(w, h, config, 3);
  const std::vector<float> frame(w * h, 0.5f);
  gen.Reset(frame, 0);
  std::vector<events::Event> events;
  for (int k = 1; k <= 1000; ++k)
    gen.Step(frame, k * 10 * kNsPerMs, &events);  // 10 s
  EXPECT_EQ(gen.signal_events(), 0);
  const double expected = 2.0 * w * h * 10.0;
  EXPECT_NEAR(static_cast<double>(events.size()), expected, 4.0 * std::sqrt(expected));
  for (std::size_t i = 1; i < events.size(); ++i)
    ASSERT_LE(events[i - 1].t_ns, events[i].t_ns);
}

TEST(EventGenerator, HotPixelsFireAtTheirRate) {
  EventCameraConfig config = Ideal();
  config.hot_pixel_fraction = 0.01;
  config.hot_pixel_rate_hz = 50.0;
  const int w = 100, h = 100;
  EventGenerator gen(w, h, config, 4);
  const std::vector<float> frame(w * h, 0.5f);
  gen.Reset(frame, 0);
  std::vector<events::Event> events;
  for (int k = 1; k <= 100; ++k)
    gen.Step(frame, k * 10 * kNsPerMs, &events);  // 1 s
  std::vector<int> count(w * h, 0);
  for (const events::Event& e : events)
    count[e.y * w + e.x]++;
  const int firing =
      static_cast<int>(std::count_if(count.begin(), count.end(), [](int c) { return c > 0; }));
  EXPECT_NEAR(firing, 100, 30);  // ~1 % of 10 000 pixels
  EXPECT_NEAR(static_cast<double>(events.size()), 50.0 * firing, 0.2 * 50.0 * firing);
}

TEST(EventGenerator, RefractoryPeriodSuppressesFollowingEvents) {
  EventCameraConfig config = Ideal();
  config.refractory_us = 500.0;
  EventGenerator gen(1, 1, config, 1);
  const float eps = static_cast<float>(config.log_eps);
  gen.Reset({std::exp(-1.0f) - eps}, 0);
  std::vector<events::Event> out;
  gen.Step({std::exp(0.0f) - eps}, kNsPerMs, &out);  // crossings at 0.25, 0.5, 0.75, 1 ms
  ASSERT_EQ(out.size(), 2u);                         // 0.25 and 0.75: 0.5 and 1.0 too close
  EXPECT_NEAR(static_cast<double>(out[1].t_ns - out[0].t_ns), 500'000.0, 2.0);
}

TEST(EventGenerator, SameSeedSameEvents) {
  auto run = [](std::uint64_t seed) {
    EventCameraConfig config;
    EventGenerator gen(32, 24, config, seed);
    std::mt19937 rng(1);
    std::vector<float> frame(32 * 24);
    for (float& v : frame)
      v = std::uniform_real_distribution<float>(0.1f, 1.0f)(rng);
    gen.Reset(frame, 0);
    std::vector<events::Event> events;
    for (int k = 1; k <= 50; ++k) {
      for (float& v : frame)
        v = std::uniform_real_distribution<float>(0.1f, 1.0f)(rng);
      gen.Step(frame, k * kNsPerMs, &events);
    }
    return events;
  };
  EXPECT_TRUE(run(9) == run(9));
  EXPECT_FALSE(run(9) == run(10));
}

}  // namespace
}  // namespace aavio::sim
