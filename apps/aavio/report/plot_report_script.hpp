#pragma once
/// The plotting scripts of `aavio report` (apps/aavio/report/*.py: plot_report.py, the page, and
/// the modules it imports), embedded at configure time.

#include <span>

namespace aavio::cli {

struct ReportScript {
  const char* file_name;
  const char* text;
};

/// All of them; the first is plot_report.py, the one to run.
std::span<const ReportScript> ReportScripts();

}  // namespace aavio::cli
