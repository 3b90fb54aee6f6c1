#pragma once
/// timings.csv: a row per tick as the run goes — its time, tracking status, stage times, map
/// size, lost reason, the events since the previous tick, the gyroscope bias used, and with
/// imu.mode=full the back-end's accelerometer bias and gravity.

#include <cstdint>
#include <fstream>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/pipeline/odometry.hpp"

namespace aavio::recording {

class TimingsCsv {
 public:
  /// The file is created at the first row.
  explicit TimingsCsv(std::string path) : path_(std::move(path)) {}

  /// Events read since the last row.
  void AddEvents(std::int64_t events) { events_since_tick_ += events; }
  /// A tick's row; `mapping_ms`: its mapping cycle's time (0 without one).
  Status Add(const pipeline::OdometryTick& tick, double mapping_ms);
  Status Close();

 private:
  std::string path_;
  std::ofstream csv_;
  std::int64_t events_since_tick_ = 0;
};

}  // namespace aavio::recording
