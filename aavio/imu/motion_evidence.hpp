#pragma once
/// Whether the IMU shows the camera moving, from its recent readings: over the last 0.1 s of
/// samples, a mean angular rate above 3 °/s or a mean specific force that differs from gravity by
/// more than 1 m/s². Both lie well above what a still MEMS IMU reads (biases up to ~1.5 °/s and
/// ~0.4 m/s²; a 0.1 s mean's noise is ~0.5 °/s and ~0.15 m/s² per axis for an MPU-6150 at
/// 1 kHz) and below what a hand-held or flown camera does while it starts moving. The magnitude
/// sees accelerations along gravity (a climb, a lift) and strong ones across it (|g + a| − g is
/// about a² / 2g); a camera that glides or starts without turning shows nothing: the evidence is
/// of motion, never of rest.

#include <deque>
#include <span>

#include "aavio/imu/imu_sample.hpp"

namespace aavio::imu {

class MotionEvidence {
 public:
  /// The samples of the next stretch, in time order (stamps not after the last are skipped).
  void Add(std::span<const ImuSample> samples);
  /// True when the last 0.1 s show motion; false without samples.
  bool Moving() const;

 private:
  std::deque<ImuSample> recent_;
};

}  // namespace aavio::imu
