#pragma once
/// The text of apps/aavio/report/plot_report.py (matplotlib plots and report.html), embedded at
/// configure time.

namespace aavio::cli {

const char* PlotReportScript();

}  // namespace aavio::cli
