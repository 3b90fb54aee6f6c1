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

// Photoreceptor bandwidth: after a step of brightness the comparator sees a first-order
// response, so the first event lags by τ·ln(1 / (1 − θ/Δ)), and τ grows as the light falls.
TEST(EventGenerator, BandwidthDelaysEventsMoreInTheDark) {
  auto first_event_lag_ns = [](float intensity_after) {
    EventCameraConfig config = Ideal();
    config.bandwidth_hz = 100.0;
    EventGenerator gen(1, 1, config, 1);
    const float eps = static_cast<float>(config.log_eps);
    const float before = intensity_after * std::exp(-1.0f) - eps;
    gen.Reset({before}, 0);
    std::vector<events::Event> out;
    gen.Step({intensity_after - eps}, 10'000, &out);  // the step, over 10 µs
    for (int k = 1; k <= 2000 && out.empty(); ++k)
      gen.Step({intensity_after - eps}, 10'000 + k * 10'000, &out);
    return out.empty() ? -1.0 : static_cast<double>(out.front().t_ns);
  };
  const double tau_bright_ns = 1e9 / (2.0 * 3.14159265 * 100.0);  // intensity 1: 1.59 ms
  const double expected = tau_bright_ns * std::log(1.0 / (1.0 - 0.25));
  EXPECT_NEAR(first_event_lag_ns(1.0f), expected, 0.05 * expected);
  EXPECT_NEAR(first_event_lag_ns(0.25f), 4.0 * expected, 0.05 * 4.0 * expected);
  // Without the low-pass the event comes within the 10 µs step.
  EventGenerator plain(1, 1, Ideal(), 1);
  plain.Reset({std::exp(-1.0f)}, 0);
  std::vector<events::Event> out;
  plain.Step({1.0f}, 10'000, &out);
  ASSERT_FALSE(out.empty());
  EXPECT_LE(out.front().t_ns, 10'000);
}

// Leak: in a still scene every pixel fires ON events at its own rate, spread log-normally.
TEST(EventGenerator, LeakFiresOnEventsAtTheConfiguredMedianRate) {
  EventCameraConfig config = Ideal();
  config.leak_rate_hz = 2.0;
  config.leak_rate_spread = 0.3;
  const int w = 40, h = 40;
  EventGenerator gen(w, h, config, 5);
  const std::vector<float> frame(w * h, 0.5f);
  gen.Reset(frame, 0);
  std::vector<events::Event> events;
  for (int k = 1; k <= 500; ++k)
    gen.Step(frame, k * 20 * kNsPerMs, &events);  // 10 s
  std::vector<int> count(w * h, 0);
  for (const events::Event& e : events) {
    EXPECT_EQ(e.polarity, 1);
    count[e.y * w + e.x]++;
  }
  std::vector<int> sorted = count;
  std::nth_element(sorted.begin(), sorted.begin() + w * h / 2, sorted.end());
  EXPECT_NEAR(sorted[w * h / 2] / 10.0, 2.0, 0.3);  // median rate
  // The spread: 0.3 decades puts the 90th-percentile pixel about ×5.9 above the 10th.
  std::sort(sorted.begin(), sorted.end());
  const double ratio = static_cast<double>(sorted[w * h * 9 / 10]) / sorted[w * h / 10];
  EXPECT_GT(ratio, 3.0);
  EXPECT_LT(ratio, 10.0);
  EXPECT_EQ(gen.noise_events(), 0);  // leak events come from the pixel's own comparator
}

// Shot noise: a dark pixel fires four times as often as a fully lit one.
TEST(EventGenerator, ShotNoiseIsMoreFrequentInTheDark) {
  EventCameraConfig config = Ideal();
  config.shot_noise_rate_hz = 5.0;
  const int w = 100, h = 50;
  EventGenerator gen(w, h, config, 6);
  std::vector<float> frame(w * h, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 2; ++x)
      frame[y * w + x] = 1e-3f;  // left half dark
  gen.Reset(frame, 0);
  std::vector<events::Event> events;
  for (int k = 1; k <= 200; ++k)
    gen.Step(frame, k * 10 * kNsPerMs, &events);  // 2 s
  double dark = 0, lit = 0;
  for (const events::Event& e : events)
    (e.x < w / 2 ? dark : lit) += 1.0;
  const double pixels = w * h / 2.0;
  EXPECT_NEAR(dark / pixels / 2.0, 5.0, 0.5);
  EXPECT_NEAR(lit / pixels / 2.0, 1.25, 0.2);
  for (std::size_t i = 1; i < events.size(); ++i)
    ASSERT_LE(events[i - 1].t_ns, events[i].t_ns);
}

// Jitter moves timestamps by about its std and keeps them sorted.
TEST(EventGenerator, TimestampJitterKeepsEventsSorted) {
  auto run = [](double jitter_us) {
    EventCameraConfig config = Ideal();
    config.timestamp_jitter_us = jitter_us;
    EventGenerator gen(1, 1, config, 2);
    gen.Reset({std::exp(-3.0f)}, 0);
    std::vector<events::Event> out;
    gen.Step({std::exp(0.0f)}, 10 * kNsPerMs, &out);  // 12 crossings over 10 ms
    return out;
  };
  const std::vector<events::Event> exact = run(0.0), jittered = run(50.0);
  ASSERT_EQ(exact.size(), jittered.size());
  double sq = 0.0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    sq += std::pow(static_cast<double>(jittered[i].t_ns - exact[i].t_ns), 2);
    if (i > 0) {
      ASSERT_LE(jittered[i - 1].t_ns, jittered[i].t_ns);
    }
  }
  const double rms_us = std::sqrt(sq / static_cast<double>(exact.size())) * 1e-3;
  EXPECT_GT(rms_us, 20.0);
  EXPECT_LT(rms_us, 100.0);
}

// A saturated readout sends at most its rate, delays events, and drops those that would wait
// longer than 1 ms.
TEST(EventGenerator, ReadoutLimitsTheRateAndDropsTheBacklog) {
  EventCameraConfig config = Ideal();
  config.max_rate_mev_s = 1.0;  // one event per µs
  const int w = 100, h = 100;
  EventGenerator gen(w, h, config, 3);
  gen.Reset(std::vector<float>(w * h, std::exp(-1.1f)), 0);
  std::vector<events::Event> out;
  gen.Step(std::vector<float>(w * h, 1.0f), 100'000, &out);  // 40 000 events in 100 µs
  EXPECT_EQ(gen.signal_events(), 40'000);
  ASSERT_FALSE(out.empty());
  for (std::size_t i = 1; i < out.size(); ++i)
    ASSERT_GE(out[i].t_ns - out[i - 1].t_ns, 1000);
  // Crossings of log −1.1 → 0 come from 0.25/1.1 to 1.0/1.1 of the 100 µs step (22.7 to 90.9
  // µs); the readout sends one per µs from the first, until the last one's 1 ms of waiting is up.
  EXPECT_NEAR(static_cast<double>(out.size()), 90.9 + 1000.0 - 22.7, 3.0);
  EXPECT_EQ(gen.dropped_events() + static_cast<std::int64_t>(out.size()), gen.signal_events());
  // The next step continues after the delayed events, in time order.
  std::vector<events::Event> next;
  gen.Step(std::vector<float>(w * h, std::exp(1.0f)), 2'000'000, &next);
  ASSERT_FALSE(next.empty());
  EXPECT_GE(next.front().t_ns, out.back().t_ns);
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
