#pragma once
/// One table of results, several runs in rows, in the forms papers and spreadsheets take:
/// Markdown, CSV or LaTeX (`aavio eval --run A --run B --table md|csv|latex`, as evo_res).

#include <string>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio::cli {

enum class TableFormat { kMarkdown, kCsv, kLatex };
Expected<TableFormat> TableFormatNamed(const std::string& name);  ///< md | csv | latex

/// `header` and every row the same width; cells as given ("" for none: "–" in Markdown and
/// LaTeX, empty in CSV). CSV quotes cells holding a comma or a quote; LaTeX escapes its specials.
std::string FormatTable(const std::vector<std::string>& header,
                        const std::vector<std::vector<std::string>>& rows, TableFormat format);

}  // namespace aavio::cli
