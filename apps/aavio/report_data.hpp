#pragma once
// What `aavio report` hands its plotting script about one run: the run's summary and
// configuration, its trajectory against the ground truth (aligned, with orientations, velocities
// and the error of each pose), its depth errors point by point (true depth, estimate, edge kind)
// and a few depth maps beside the ground truth's, as JSON plus raw float images.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "aavio/common/status.hpp"
#include "cli.hpp"

namespace aavio::cli {

struct ReportRun {
  std::string dir, name, calibration;  ///< calibration: --calib, for runs that name none
};

/// At most this many depth maps of a run are drawn beside their ground truth.
inline constexpr int kReportDepthFrames = 3;

/// The run's data as JSON; depth images go to `data_dir` as `<prefix>_*.f32` (float32, row-major,
/// NaN where there is no depth), named in the JSON with their width and height. Without ground
/// truth, the run's own files only (a note on ctx.err says so).
Expected<nlohmann::json> GatherReportRun(const ReportRun& run,
                                         const std::filesystem::path& data_dir,
                                         const std::string& prefix, Context& ctx);

}  // namespace aavio::cli
