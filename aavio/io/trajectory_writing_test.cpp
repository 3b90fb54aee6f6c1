#include "aavio/io/trajectory_writing.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "aavio/geometry/rotation.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

std::vector<geometry::StampedPose> Poses() {
  std::vector<geometry::StampedPose> poses;
  for (int i = 0; i < 5; ++i) {
    geometry::RigidTransform T;
    T.R = geometry::ExpSO3(Eigen::Vector3d(0.1 * i, -0.2, 0.3));
    T.t = {0.5 * i, 1.0, -2.0};
    poses.push_back({1'700'000'000'000'000'000LL + i * 10'000'000LL, T});
  }
  return poses;
}

// Every format aavio writes reads back (TUM in s and ns, EuRoC and EvSLAM through the
// auto-detecting reader) to the same poses; KITTI's matrix rows and its times file are as KITTI's
// tools expect. One set of format names for reading and writing; auto is for reading only.
TEST(TrajectoryWriting, FormatNamesAreTheReadersAndAllButAutoWrite) {
  for (TrajectoryFormat format :
       {TrajectoryFormat::kAuto, TrajectoryFormat::kTum, TrajectoryFormat::kTumNs,
        TrajectoryFormat::kEuroc, TrajectoryFormat::kEvslam, TrajectoryFormat::kKitti}) {
    const std::string name = TrajectoryFormatName(format);
    Expected<TrajectoryFormat> read = TrajectoryFormatNamed(name);
    ASSERT_TRUE(read.ok()) << name << ": " << read.status().message();
    EXPECT_EQ(*read, format);
    EXPECT_EQ(WritableTrajectoryFormat(name).ok(), format != TrajectoryFormat::kAuto) << name;
  }
  EXPECT_FALSE(TrajectoryFormatNamed("csv").ok());
  EXPECT_EQ(TrajectoryFileName(TrajectoryFormat::kEuroc), "trajectory_euroc.csv");
}

TEST(TrajectoryWriting, EveryFormatReadsBack) {
  const auto poses = Poses();
  const auto velocities = geometry::EstimateVelocities(poses, 20'000'000);
  const auto dir = testing::ScratchDir();
  for (TrajectoryFormat format : {TrajectoryFormat::kTum, TrajectoryFormat::kTumNs,
                                  TrajectoryFormat::kEuroc, TrajectoryFormat::kEvslam}) {
    const std::string path = (dir / TrajectoryFileName(format)).string();
    ASSERT_TRUE(WriteTrajectory(path, poses, velocities, format).ok());
    Expected<std::vector<geometry::StampedPose>> back =
        ReadTrajectory(path, TrajectoryFormat::kAuto);
    ASSERT_TRUE(back.ok()) << TrajectoryFormatName(format) << ": " << back.status().message();
    ASSERT_EQ(back->size(), poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
      EXPECT_EQ((*back)[i].t_ns, poses[i].t_ns);
      EXPECT_LT(((*back)[i].T_world_body.t - poses[i].T_world_body.t).norm(), 1e-8);
      EXPECT_LT(((*back)[i].T_world_body.R - poses[i].T_world_body.R).norm(), 1e-8);
    }
  }
  // EvSLAM: the body-frame velocity after the quaternion; 0.5 m/s along world x here.
  const std::string evslam = testing::ReadAll(dir / "trajectory_evslam.txt");
  EXPECT_NE(evslam.find("1700000000.020000000 1.000000000 1.000000000 -2.000000000"),
            std::string::npos)
      << evslam;
  const std::string kitti_path = (dir / "trajectory_kitti.txt").string();
  ASSERT_TRUE(WriteTrajectory(kitti_path, poses, {}, TrajectoryFormat::kKitti).ok());
  const std::string kitti = testing::ReadAll(kitti_path);
  EXPECT_EQ(std::count(kitti.begin(), kitti.end(), '\n'), 5);
  EXPECT_NE(kitti.find("1.000000000e+00 "), std::string::npos);  // the t of pose 2, first row
  EXPECT_EQ(testing::ReadAll(dir / "trajectory_kitti_times.txt").substr(0, 31),
            "1700000000.000000000\n1700000000");
  // KITTI cannot be read back (no stamps): refused by name.
  EXPECT_NE(ReadTrajectory(kitti_path, TrajectoryFormat::kAuto).status().message().find("KITTI"),
            std::string::npos);
}

TEST(TrajectoryWriting, StampsInSecondsOrNanosecondsAndBadOnes) {
  const auto dir = testing::ScratchDir();
  Expected<std::vector<TimeNs>> s =
      ReadStamps(testing::WriteFile(dir / "s.txt", "# ref\n1.5\n1.51\n1.52 extra columns\n"));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(*s, (std::vector<TimeNs>{1'500'000'000, 1'510'000'000, 1'520'000'000}));
  s = ReadStamps(testing::WriteFile(dir / "ns.txt", "1500000000\n1510000000\n"));
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->back(), 1'510'000'000);
  EXPECT_NE(ReadStamps(testing::WriteFile(dir / "u.txt", "2.0\n1.0\n"))
                .status()
                .message()
                .find("u.txt:2: stamp 1.0 is not after"),
            std::string::npos);
  EXPECT_NE(ReadStamps(testing::WriteFile(dir / "e.txt", "# none\n"))
                .status()
                .message()
                .find("no stamps"),
            std::string::npos);
}

}  // namespace
}  // namespace aavio::io
