// DSEC cam_to_cam.yaml fixtures come from tests/fixtures/write_dsec_cam_to_cam.py, run with
// Debian's /usr/bin/python3 and PyYAML: an independent writer.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "aavio/io/calibration.hpp"
#include "tests/test_utils.hpp"

namespace aavio::io {
namespace {

class DsecCalibrationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(testing::ScratchDir());
    const std::string command = "/usr/bin/python3 " AAVIO_SOURCE_DIR
                                "/tests/fixtures/write_dsec_cam_to_cam.py " +
                                dir_->string();
    status_ = std::system(command.c_str());
  }
  static void TearDownTestSuite() { delete dir_; }
  void SetUp() override {
    ASSERT_EQ(status_, 0) << "the fixture writer failed; scripts/setup.sh installs python3-yaml "
                             "and python3-numpy";
  }
  static std::string Fixture(const char* name) { return (*dir_ / name).string(); }

  static std::filesystem::path* dir_;
  static int status_;
};
std::filesystem::path* DsecCalibrationTest::dir_ = nullptr;
int DsecCalibrationTest::status_ = -1;

TEST_F(DsecCalibrationTest, LoadsAndSatisfiesTheConsistencyRelations) {
  Expected<LoadedCalibration> c = LoadCalibration(Fixture("good.yaml"));
  ASSERT_TRUE(c.ok()) << c.status().message();
  EXPECT_EQ(c->format, "dsec");
  const geometry::StereoRig& rig = c->rig;
  EXPECT_EQ(rig.width(), 640);
  EXPECT_EQ(rig.height(), 480);
  EXPECT_NEAR(rig.baseline_m(), 0.5992, 1e-12);  // B = 1/Q[3][2]
  EXPECT_DOUBLE_EQ(rig.focal_px(), 583.31);
  EXPECT_DOUBLE_EQ(rig.cx_left(), 336.83);
  EXPECT_DOUBLE_EQ(rig.cy(), 220.91);
  EXPECT_DOUBLE_EQ(rig.left().intrinsics().fx, 556.72);  // cam0
  EXPECT_DOUBLE_EQ(rig.right().intrinsics().fx, 553.2);  // cam3
  EXPECT_DOUBLE_EQ(rig.left().intrinsics().coeffs[0], -0.098);
  // docs/io.md: with T_30 = T_32 T_21 T_10, R_rect3 R_30 R_rect0ᵀ = I and
  // R_rect3 t_30 = (−B, 0, 0).
  const geometry::RigidTransform& T_30 = rig.T_right_left();
  EXPECT_LT(geometry::LogSO3(rig.R_rect_right_right() * T_30.R * rig.R_rect_left_left().transpose())
                .norm(),
            1e-9);
  EXPECT_LT((rig.R_rect_right_right() * T_30.t - Eigen::Vector3d(-0.5992, 0, 0)).norm(), 1e-9);
  EXPECT_DOUBLE_EQ(rig.P_right()(0, 3), -583.31 * rig.baseline_m());
  EXPECT_FALSE(rig.T_imu_left().has_value());
}

TEST_F(DsecCalibrationTest, SequenceFolderAndCalibrationFolderAreFound) {
  const auto seq = testing::ScratchDir();
  std::filesystem::create_directories(seq / "calibration");
  std::filesystem::copy_file(Fixture("good.yaml"), seq / "calibration" / "cam_to_cam.yaml");
  EXPECT_TRUE(LoadCalibration(seq.string()).ok());
  EXPECT_TRUE(LoadCalibration((seq / "calibration").string()).ok());
}

TEST_F(DsecCalibrationTest, RefusesBrokenFiles) {
  const std::vector<std::pair<const char*, const char*>> cases = {
      {"inconsistent.yaml", "inconsistent stereo calibration: R_rect3 * R_30 * R_rect0^T is 0.57"},
      {"missing_key.yaml", "missing key 'extrinsics.R_rect3'"},
      {"camera_matrix_3x3.yaml",
       "intrinsics.cam0.camera_matrix must list 4 numbers [fx, fy, cx, cy], got 9"},
      {"not_rotation.yaml", "extrinsics.R_rect0 is not a rotation"},
      {"negative_baseline.yaml", "cams_03[3][2] = -1.66"},
  };
  for (const auto& [file, expected] : cases) {
    Expected<LoadedCalibration> c = LoadCalibration(Fixture(file));
    ASSERT_FALSE(c.ok()) << file;
    EXPECT_NE(c.status().message().find(expected), std::string::npos)
        << file << ": " << c.status().message();
    EXPECT_NE(c.status().message().find(file), std::string::npos) << "names the file";
  }
}

}  // namespace
}  // namespace aavio::io
