#include "aavio/events/time_surface.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "aavio/events/test_events.hpp"
#include "aavio/events/ts_images.hpp"

namespace aavio::events {
namespace {

TEST(TimeSurface, FastEqualsBruteForceOnRandomEvents) {
  const int w = 48, h = 36;
  const TimeNs t0 = 1'500'000'000LL * kNsPerS;  // rpg-like absolute stamps
  const std::vector<Event> events = testing::RandomEvents(3000, w, h, t0, 200 * kNsPerMs, 3);
  TimeSurface ts(w, h, t0);
  std::size_t inserted = 0;
  int compared = 0;
  for (TimeNs tick = t0 + 10 * kNsPerMs; tick <= t0 + 200 * kNsPerMs; tick += 10 * kNsPerMs) {
    std::size_t end = inserted;
    while (end < events.size() && events[end].t_ns <= tick)
      ++end;
    ASSERT_TRUE(ts.Insert(std::span(events).subspan(inserted, end - inserted)).ok());
    inserted = end;
    cv::Mat fast;
    ts.Render(tick, 30.0, &fast);
    const cv::Mat brute = BruteForceTimeSurface(events, w, h, tick, 30.0);
    // Identical except where 255·T lies within ~1e-3 of a rounding boundary (float stamps).
    cv::Mat diff;
    cv::absdiff(fast, brute, diff);
    double max_diff = 0.0;
    cv::minMaxLoc(diff, nullptr, &max_diff);
    EXPECT_LE(max_diff, 1.0);
    EXPECT_LE(cv::countNonZero(diff), w * h / 200) << "at tick " << tick;
    ++compared;
  }
  EXPECT_EQ(compared, 20);
}

TEST(TimeSurface, ValuesFollowTheDefinition) {
  TimeSurface ts(4, 1, 0);
  const std::vector<Event> events = {
      {0, 0, 0, 1}, {10 * kNsPerMs, 1, 0, 0}, {30 * kNsPerMs, 2, 0, 1}};
  ASSERT_TRUE(ts.Insert(events).ok());
  cv::Mat image;
  ts.Render(30 * kNsPerMs, 10.0, &image);
  EXPECT_EQ(image.at<std::uint8_t>(0, 2), 255);                                // just now
  EXPECT_EQ(image.at<std::uint8_t>(0, 1), std::lround(255 * std::exp(-2.0)));  // 2τ ago: 35
  EXPECT_EQ(image.at<std::uint8_t>(0, 0), std::lround(255 * std::exp(-3.0)));  // 3τ ago: 13
  EXPECT_EQ(image.at<std::uint8_t>(0, 3), 0);                                  // never
  ts.Render(30 * kNsPerMs + 70 * kNsPerMs, 10.0, &image);  // 7τ later: all gone
  EXPECT_EQ(cv::countNonZero(image), 0);
}

TEST(TimeSurface, RefusesEventsOutOfOrderOrOutsideTheSensor) {
  TimeSurface ts(10, 10, 0);
  const std::vector<Event> late = {{5, 1, 1, 1}, {4, 1, 1, 1}};
  const Status order = ts.Insert(late);
  EXPECT_FALSE(order.ok());
  EXPECT_NE(order.message().find("out of order"), std::string::npos) << order.message();
  const std::vector<Event> outside = {{9, 10, 3, 1}};
  const Status bounds = ts.Insert(outside);
  EXPECT_NE(bounds.message().find("outside the 10×10 sensor"), std::string::npos)
      << bounds.message();
}

TEST(TsImages, NegativeTsAndGradients) {
  // A vertical ridge of events at column 10 on an empty surface.
  cv::Mat ts(20, 21, CV_8UC1, cv::Scalar(0));
  ts.col(10).setTo(200);
  cv::Mat negative;
  NegativeTs(ts, &negative);
  // The Gaussian smears the ridge (above 255 − 200 on it); empty pixels near it are below 255 (a
  // slope towards the edge), far ones 255.
  EXPECT_GT(negative.at<std::uint8_t>(5, 10), 55);
  EXPECT_LT(negative.at<std::uint8_t>(5, 10), 255);
  EXPECT_LT(negative.at<std::uint8_t>(5, 8), 255);
  EXPECT_EQ(negative.at<std::uint8_t>(5, 0), 255);
  cv::Mat du, dv;
  SobelGradients(negative, &du, &dv);
  EXPECT_EQ(du.type(), CV_32FC1);
  EXPECT_LT(du.at<float>(5, 9), 0.0f);  // falling towards the ridge from the left
  EXPECT_GT(du.at<float>(5, 11), 0.0f);
  EXPECT_FLOAT_EQ(dv.at<float>(5, 9), 0.0f);
  // Sobel/8 is the per-pixel slope: a ramp of 1 per pixel gives 1.
  cv::Mat ramp(5, 5, CV_8UC1);
  for (int x = 0; x < 5; ++x)
    ramp.col(x).setTo(10 * x);
  SobelGradients(ramp, &du, &dv);
  EXPECT_FLOAT_EQ(du.at<float>(2, 2), 10.0f);
}

TEST(NegativeTs, IntegerGradientsEqualFloatSobelEverywhere) {
  // Sizes around the vector widths, the smallest the integer pass takes, and a view into a
  // larger image (rows addressed by its step; reflected at its own borders, so compared with
  // its copy); the extremes 0 and 255 beside each other.
  cv::RNG rng(7);
  cv::Mat large(40, 80, CV_8UC1);
  rng.fill(large, cv::RNG::UNIFORM, 0, 256);
  std::vector<cv::Mat> images = {large(cv::Rect(3, 2, 53, 37)), cv::Mat(2, 3, CV_8UC1),
                                 cv::Mat(5, 33, CV_8UC1),       cv::Mat(480, 640, CV_8UC1),
                                 cv::Mat(1, 7, CV_8UC1),        cv::Mat(6, 2, CV_8UC1)};
  for (std::size_t i = 1; i < images.size(); ++i)
    rng.fill(images[i], cv::RNG::UNIFORM, 0, 256);
  cv::Mat stripes(9, 35, CV_8UC1, cv::Scalar(0));
  for (int x = 0; x < stripes.cols; x += 2)
    stripes.col(x).setTo(255);
  images.push_back(stripes);
  images.push_back(stripes.t());
  for (const cv::Mat& image : images) {
    cv::Mat du, dv, float_du, float_dv;
    SobelGradients(image, &du, &dv);
    const cv::Mat own = image.clone();
    cv::Sobel(own, float_du, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT_101);
    cv::Sobel(own, float_dv, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT_101);
    ASSERT_EQ(du.type(), CV_32FC1);
    ASSERT_EQ(du.size(), image.size());
    // Borders included.
    EXPECT_EQ(cv::norm(du, float_du, cv::NORM_INF), 0.0) << image.cols << "x" << image.rows;
    EXPECT_EQ(cv::norm(dv, float_dv, cv::NORM_INF), 0.0) << image.cols << "x" << image.rows;
  }
}

}  // namespace
}  // namespace aavio::events
