#pragma once
// The event/IMU fixtures of tests/fixtures/write_event_fixtures.py (h5py, rosbag: independent
// writers) and readers of the raw expected-content files it writes beside them.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "aavio/events/event.hpp"
#include "aavio/geometry/pose_buffer.hpp"
#include "aavio/imu/imu_sample.hpp"
#include "aavio/io/streams.hpp"

namespace aavio::testing {

/// build/test_fixtures/events, written once (CTest runs the writer as a setup fixture; a test
/// binary started by hand writes them itself when they are missing).
inline std::string EventFixtureDir() {
  const std::filesystem::path dir =
      std::filesystem::path(AAVIO_TEST_TMP_DIR).parent_path() / "test_fixtures" / "events";
  if (!std::filesystem::exists(dir / "done")) {
    const std::string command = "flock " + dir.parent_path().string() +
                                ".lock /usr/bin/python3 " AAVIO_SOURCE_DIR
                                "/tests/fixtures/write_event_fixtures.py " +
                                dir.string() + " > /dev/null";
    std::filesystem::create_directories(dir.parent_path());
    if (!std::filesystem::exists(dir / "done")) {
      EXPECT_EQ(std::system(command.c_str()), 0)
          << "the fixture writer failed; scripts/setup.sh installs python3-h5py, "
             "python3-hdf5plugin, python3-rosbag and python3-genpy";
    }
  }
  return dir.string();
}

inline std::string Fixture(const std::string& name) {
  return EventFixtureDir() + "/" + name;
}

inline std::vector<char> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

/// <name>.events.bin: int64 t_ns, uint16 x, uint16 y, uint8 p.
inline std::vector<events::Event> ExpectedEvents(const std::string& name) {
  const std::vector<char> bytes = ReadBytes(Fixture(name + ".events.bin"));
  EXPECT_EQ(bytes.size() % 13, 0u);
  std::vector<events::Event> out(bytes.size() / 13);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char* p = bytes.data() + 13 * i;
    std::memcpy(&out[i].t_ns, p, 8);
    std::memcpy(&out[i].x, p + 8, 2);
    std::memcpy(&out[i].y, p + 10, 2);
    out[i].polarity = static_cast<std::uint8_t>(p[12]);
  }
  return out;
}

/// <name>.imu.bin: int64 t_ns, 3 float64 gyro, 3 float64 accel.
inline std::vector<imu::ImuSample> ExpectedImu(const std::string& name) {
  const std::vector<char> bytes = ReadBytes(Fixture(name + ".imu.bin"));
  std::vector<imu::ImuSample> out(bytes.size() / 56);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char* p = bytes.data() + 56 * i;
    std::memcpy(&out[i].t_ns, p, 8);
    std::memcpy(out[i].gyro_rad_s.data(), p + 8, 24);
    std::memcpy(out[i].accel_m_s2.data(), p + 32, 24);
  }
  return out;
}

/// <name>.poses.bin: int64 t_ns, 3 float64 position, 4 float64 quaternion (x y z w).
inline std::vector<geometry::StampedPose> ExpectedPoses(const std::string& name) {
  const std::vector<char> bytes = ReadBytes(Fixture(name + ".poses.bin"));
  std::vector<geometry::StampedPose> out(bytes.size() / 64);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char* p = bytes.data() + 64 * i;
    double v[7];
    std::memcpy(&out[i].t_ns, p, 8);
    std::memcpy(v, p + 8, 56);
    out[i].T_world_body = {
        Eigen::Quaterniond(v[6], v[3], v[4], v[5]).normalized().toRotationMatrix(),
        Eigen::Vector3d(v[0], v[1], v[2])};
  }
  return out;
}

/// Reads a stream to its end in packets of `packet_ns` from `start_ns` (default: its first
/// stamp minus one), failing the test on any error.
template <typename T>
std::vector<T> ReadAllOf(io::Stream<T>& stream, TimeNs packet_ns,
                         std::optional<TimeNs> start_ns = {}) {
  std::vector<T> out;
  TimeNs t = start_ns ? *start_ns : stream.info().t_first_ns - 1;
  while (!stream.AtEnd()) {
    t += packet_ns;
    Status s = stream.ReadUntil(t, &out);
    EXPECT_TRUE(s.ok()) << s.message();
    if (!s.ok()) break;
  }
  return out;
}

}  // namespace aavio::testing
