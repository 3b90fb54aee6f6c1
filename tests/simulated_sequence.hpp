#pragma once
// A simulated sequence held in memory for library tests: its description, rig, packets (as a
// SequenceReader gives them) and ground-truth poses. Failures are reported as test failures and
// leave the fields empty, so that a test can skip cleanly.

#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "aavio/io/calibration.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/sim/simulator.hpp"
#include "tests/test_utils.hpp"

namespace aavio::testing {

struct SimulatedSequence {
  io::SequenceDescription description;
  std::optional<geometry::StereoRig> rig;
  TimeNs start_ns = 0;
  std::vector<io::SensorPacket> packets;
  std::vector<geometry::StampedPose> truth;
};

/// Simulates `preset` (typical sensor) into a scratch folder and reads it back whole.
inline SimulatedSequence Simulate(const std::string& preset, double duration_s, std::uint64_t seed,
                                  TimeNs packet_ns = 10 * kNsPerMs) {
  SimulatedSequence s;
  sim::SimulationRequest request;
  request.preset = preset;
  request.duration_s = duration_s;
  request.seed = seed;
  request.out_dir = (ScratchDir() / ("simulated_" + preset)).string();
  Expected<sim::SimulationReport> report = sim::Simulate(request);
  EXPECT_TRUE(report.ok()) << report.status().message();
  if (!report.ok()) return s;
  Expected<io::SequenceDescription> d = io::DescribeSequence(report->sequence_yaml);
  EXPECT_TRUE(d.ok()) << d.status().message();
  if (!d.ok()) return s;
  s.description = *d;
  Expected<io::LoadedCalibration> calibration = io::LoadCalibration(d->calibration);
  EXPECT_TRUE(calibration.ok()) << calibration.status().message();
  if (!calibration.ok()) return s;
  s.rig = calibration->rig;
  io::SequenceReaderOptions options;
  options.packet_ns = packet_ns;
  auto reader = io::SequenceReader::Open(*d, options);
  EXPECT_TRUE(reader.ok()) << reader.status().message();
  if (!reader.ok()) return s;
  s.start_ns = (*reader)->start_ns();
  io::SensorPacket packet;
  while (true) {
    Expected<bool> more = (*reader)->Next(&packet);
    EXPECT_TRUE(more.ok());
    if (!more.ok() || !*more) break;
    s.packets.push_back(packet);
  }
  if (d->gt_trajectory) {
    Expected<std::vector<geometry::StampedPose>> truth =
        io::ReadTumTrajectory(d->gt_trajectory->path);
    EXPECT_TRUE(truth.ok());
    if (truth.ok()) s.truth = *truth;
  }
  return s;
}

/// The mini preset's twin (160×120 px, typical sensor) of `duration_s` from `seed`, simulated once
/// per test program and kept for every test that asks for the same one.
inline const SimulatedSequence& MiniTwin(double duration_s, std::uint64_t seed,
                                         TimeNs packet_ns = 10 * kNsPerMs) {
  static std::map<std::tuple<double, std::uint64_t, TimeNs>, SimulatedSequence> twins;
  const auto key = std::make_tuple(duration_s, seed, packet_ns);
  auto it = twins.find(key);
  if (it == twins.end())
    it = twins.emplace(key, Simulate("mini", duration_s, seed, packet_ns)).first;
  return it->second;
}

}  // namespace aavio::testing
