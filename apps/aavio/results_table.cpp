#include "results_table.hpp"

namespace aavio::cli {
namespace {

std::string CsvCell(const std::string& cell) {
  if (cell.find_first_of(",\"\n") == std::string::npos) return cell;
  std::string out = "\"";
  for (const char c : cell)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string LatexCell(const std::string& cell) {
  if (cell.empty()) return "--";
  std::string out;
  for (const char c : cell) {
    switch (c) {
      case '%':
      case '&':
      case '_':
      case '#':
      case '$':
      case '{':
      case '}':
        out += '\\';
        out += c;
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string MarkdownCell(const std::string& cell) {
  if (cell.empty()) return "–";
  std::string out;
  for (const char c : cell)
    out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

Expected<TableFormat> TableFormatNamed(const std::string& name) {
  if (name == "md" || name == "markdown") return TableFormat::kMarkdown;
  if (name == "csv") return TableFormat::kCsv;
  if (name == "latex" || name == "tex") return TableFormat::kLatex;
  return InvalidArgument("table format '" + name + "' is none of md, csv, latex");
}

std::string FormatTable(const std::vector<std::string>& header,
                        const std::vector<std::vector<std::string>>& rows, TableFormat format) {
  std::string out;
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      switch (format) {
        case TableFormat::kMarkdown:
          s += (i == 0 ? "| " : " | ") + MarkdownCell(cells[i]);
          break;
        case TableFormat::kCsv:
          s += (i == 0 ? "" : ",") + CsvCell(cells[i]);
          break;
        case TableFormat::kLatex:
          s += (i == 0 ? "" : " & ") + LatexCell(cells[i]);
          break;
      }
    }
    switch (format) {
      case TableFormat::kMarkdown:
        return s + " |\n";
      case TableFormat::kCsv:
        return s + "\n";
      case TableFormat::kLatex:
        return s + " \\\\\n";
    }
    return s;
  };
  if (format == TableFormat::kLatex) {
    out += "\\begin{tabular}{l" + std::string(header.size() > 0 ? header.size() - 1 : 0, 'r') +
           "}\n\\hline\n";
  }
  out += line(header);
  if (format == TableFormat::kMarkdown) {
    out += "|";
    for (std::size_t i = 0; i < header.size(); ++i)
      out += i == 0 ? "---|" : "---:|";
    out += "\n";
  }
  if (format == TableFormat::kLatex) out += "\\hline\n";
  for (const std::vector<std::string>& row : rows)
    out += line(row);
  if (format == TableFormat::kLatex) out += "\\hline\n\\end{tabular}\n";
  return out;
}

}  // namespace aavio::cli
