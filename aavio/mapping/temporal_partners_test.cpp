// Temporal stereo's partners: the newest observation far enough, the cross-check partner beyond
// it, and the history that keeps the recent ones.
#include "aavio/mapping/temporal_partners.hpp"

#include <gtest/gtest.h>

namespace aavio::mapping {
namespace {

// Observations 0.3 m apart along x (oldest first): the partner is the newest at least
// min_translation_m from now, the check partner the newest older one at least
// kCrossCheckSpacing × min_translation_m beyond it.
TEST(TemporalPartners, AreTheNewestFarEnoughAndTheCrossCheckBeyond) {
  std::vector<PosedObservation> history(6);
  for (int i = 0; i < 6; ++i)
    history[static_cast<std::size_t>(i)].T_world_obs.t = {0.3 * i, 0.0, 0.0};
  geometry::RigidTransform now;
  now.t = {1.8, 0.0, 0.0};  // 0.3 m beyond the newest
  TemporalStereoConfig config;
  config.min_translation_m = 0.5;
  TemporalPartners partners = FindTemporalPartners(history, now, config);
  EXPECT_EQ(partners.main, &history[4]);  // 0.6 m back
  EXPECT_EQ(partners.check, nullptr);     // cross-check off
  config.cross_check_px = 1.0;
  partners = FindTemporalPartners(history, now, config);
  EXPECT_EQ(partners.main, &history[4]);
  EXPECT_EQ(partners.check, &history[3]);  // 0.3 m beyond it: baselines 0.6 and 0.9 m
  config.min_translation_m = 2.0;
  partners = FindTemporalPartners(history, now, config);
  EXPECT_EQ(partners.main, nullptr);  // every observation within 1.8 m
  config.min_translation_m = 0.9;
  partners = FindTemporalPartners(history, now, config);
  EXPECT_EQ(partners.main, &history[3]);   // 0.9 m back
  EXPECT_EQ(partners.check, &history[1]);  // 0.6 m beyond it, the first at least 0.45 m
  now.t = {0.7, 0.0, 0.0};                 // every observation within 0.9 m
  EXPECT_EQ(FindTemporalPartners(history, now, config).main, nullptr);
}

// The history: the newest kTemporalHistoryLength observations, only their AA maps, partners
// handed out as copies, all forgotten on Clear.
TEST(TemporalHistory, KeepsTheNewestAndHandsOutPartnerCopies) {
  TemporalStereoConfig config;
  config.min_translation_m = 0.5;
  config.cross_check_px = 1.0;
  TemporalHistory history(config);
  for (int i = 0; i < kTemporalHistoryLength + 5; ++i) {
    auto obs = std::make_shared<events::Observation>();
    obs->t_ns = i;
    obs->aa_map = cv::Mat(4, 4, CV_32FC1, cv::Scalar(i));
    obs->ts_left = cv::Mat(4, 4, CV_8UC1, cv::Scalar(1));
    PosedObservation posed{obs, {}};
    posed.T_world_obs.t = {0.3 * i, 0.0, 0.0};
    history.Remember(posed);
  }
  geometry::RigidTransform now;
  now.t = {0.3 * (kTemporalHistoryLength + 5), 0.0, 0.0};
  TemporalHistory::Partners partners = history.PartnersFor(now);
  ASSERT_TRUE(partners.main.has_value());
  ASSERT_TRUE(partners.check.has_value());
  const TimeNs newest = kTemporalHistoryLength + 4;
  EXPECT_EQ(partners.main->obs->t_ns, newest - 1);  // 0.6 m back
  EXPECT_EQ(partners.check->obs->t_ns, newest - 2);
  EXPECT_EQ(partners.main->obs->aa_map.at<float>(0, 0), static_cast<float>(newest - 1));
  EXPECT_TRUE(partners.main->obs->ts_left.empty());  // only the AA map is kept
  // Only the newest kTemporalHistoryLength are kept: from the newest's place, 5.75 m back
  // would be observation 4 (6 m back), which is gone; observation 5 is 5.7 m back.
  now.t = {0.3 * newest, 0.0, 0.0};
  config.cross_check_px = 0.0;
  auto partner_beyond = [&](double min_translation_m) -> std::optional<TimeNs> {
    config.min_translation_m = min_translation_m;
    TemporalHistory line(config);
    for (int i = 0; i < kTemporalHistoryLength + 5; ++i) {
      auto obs = std::make_shared<events::Observation>();
      obs->t_ns = i;
      line.Remember({obs, geometry::RigidTransform(Eigen::Matrix3d::Identity(), {0.3 * i, 0, 0})});
    }
    const TemporalHistory::Partners found = line.PartnersFor(now);
    if (!found.main) return std::nullopt;
    return found.main->obs->t_ns;
  };
  EXPECT_EQ(partner_beyond(5.65), std::optional<TimeNs>(5));
  EXPECT_EQ(partner_beyond(5.75), std::nullopt);
  // The copies outlive later observations and a Clear.
  history.Clear();
  EXPECT_EQ(partners.main->obs->t_ns, newest - 1);
  EXPECT_FALSE(history.PartnersFor(now).main.has_value());
}

}  // namespace
}  // namespace aavio::mapping
