#include "results_table.hpp"

#include <gtest/gtest.h>

namespace aavio::cli {
namespace {

TEST(ResultsTable, MarkdownCsvAndLatexWithTheirEscapes) {
  const std::vector<std::string> header = {"run", "ATE [%]"};
  const std::vector<std::vector<std::string>> rows = {{"a_b, c|d", "1.50"}, {"e", ""}};
  EXPECT_EQ(FormatTable(header, rows, TableFormat::kMarkdown),
            "| run | ATE [%] |\n|---|---:|\n| a_b, c\\|d | 1.50 |\n| e | – |\n");
  EXPECT_EQ(FormatTable(header, rows, TableFormat::kCsv), "run,ATE [%]\n\"a_b, c|d\",1.50\ne,\n");
  EXPECT_EQ(FormatTable(header, rows, TableFormat::kLatex),
            "\\begin{tabular}{lr}\n\\hline\nrun & ATE [\\%] \\\\\n\\hline\n"
            "a\\_b, c|d & 1.50 \\\\\ne & -- \\\\\n\\hline\n\\end{tabular}\n");
  EXPECT_FALSE(TableFormatNamed("xlsx").ok());
  EXPECT_EQ(*TableFormatNamed("latex"), TableFormat::kLatex);
}

}  // namespace
}  // namespace aavio::cli
