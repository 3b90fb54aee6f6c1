#include "aavio/io/yaml_reading.hpp"

#include <charconv>
#include <cmath>
#include <map>

#include "aavio/io/file_checks.hpp"

namespace aavio::io::yaml {

namespace {

std::string ShapeText(int rows, int cols) {
  return std::to_string(rows) + "x" + std::to_string(cols);
}

/// A key given twice in one mapping: YAML forbids it, and the parser would keep the first silently.
Status CheckDuplicateKeys(const YAML::Node& node, const std::string& origin, int depth = 0) {
  if (depth > 64) return ParseError(origin + ": nested more than 64 levels deep");
  if (node.IsSequence()) {
    for (const YAML::Node& item : node)
      AAVIO_RETURN_IF_ERROR(CheckDuplicateKeys(item, origin, depth + 1));
  } else if (node.IsMap()) {
    std::map<std::string, int> lines;
    for (const auto& pair : node) {
      if (pair.first.IsScalar()) {
        const int line = pair.first.Mark().line + 1;
        auto [it, inserted] = lines.emplace(pair.first.Scalar(), line);
        if (!inserted) {
          return ParseError(origin + ":" + std::to_string(line) + ": key '" + pair.first.Scalar() +
                            "' is given twice (first on line " + std::to_string(it->second) +
                            "); keep one");
        }
      }
      AAVIO_RETURN_IF_ERROR(CheckDuplicateKeys(pair.second, origin, depth + 1));
    }
  }
  return Status::Ok();
}

}  // namespace

Expected<YAML::Node> LoadText(const std::string& text, const std::string& origin) {
  try {
    YAML::Node root = YAML::Load(text);
    if (!root || root.IsNull()) return ParseError(origin + ": file is empty");
    if (!root.IsMap()) {
      return ParseError(Where(origin, root) + ": expected a mapping of keys at the top level");
    }
    AAVIO_RETURN_IF_ERROR(CheckDuplicateKeys(root, origin));
    return root;
  } catch (const YAML::Exception& e) {
    return ParseError(origin + ":" + std::to_string(e.mark.line + 1) + ":" +
                      std::to_string(e.mark.column + 1) +
                      ": YAML syntax error: " + PrintableExcerpt(e.msg, 200));
  }
}

Expected<YAML::Node> LoadFile(const std::string& path) {
  Expected<std::string> text = ReadBoundedFile(path, kMaxSettingsFileBytes, "YAML file");
  if (!text) return text.status();
  return LoadText(*text, path);
}

std::string Where(const std::string& file, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0) return file;
  return file + ":" + std::to_string(mark.line + 1);
}

Expected<YAML::Node> Child(const YAML::Node& parent, const std::string& key,
                           const std::string& file, const std::string& hint) {
  if (!parent.IsMap()) return ParseError(Where(file, parent) + ": expected a mapping");
  YAML::Node child = parent[key];
  if (!child) {
    return NotFound(file + ": missing key '" + key + "'" + (hint.empty() ? "" : " (" + hint + ")"));
  }
  return child;
}

Expected<double> ToDouble(const YAML::Node& node, const std::string& file, const std::string& key) {
  if (!node.IsScalar()) {
    return ParseError(Where(file, node) + ": " + key + " must be a number");
  }
  const std::string& text = node.Scalar();
  double value = 0.0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (begin != end && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || text.empty() || !std::isfinite(value)) {
    return ParseError(Where(file, node) + ": " + key + " = '" + text + "' is not a finite number");
  }
  return value;
}

Expected<int> ToInt(const YAML::Node& node, const std::string& file, const std::string& key) {
  if (!node.IsScalar()) return ParseError(Where(file, node) + ": " + key + " must be an integer");
  const std::string& text = node.Scalar();
  int value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || text.empty()) {
    return ParseError(Where(file, node) + ": " + key + " = '" + text + "' is not an integer");
  }
  return value;
}

Expected<std::string> ToString(const YAML::Node& node, const std::string& file,
                               const std::string& key) {
  if (!node.IsScalar()) return ParseError(Where(file, node) + ": " + key + " must be a string");
  return node.Scalar();
}

Expected<std::vector<double>> ToNumbers(const YAML::Node& node, const std::string& file,
                                        const std::string& key) {
  if (!node.IsSequence()) {
    return ParseError(Where(file, node) + ": " + key + " must be a list of numbers [a, b, ...]");
  }
  std::vector<double> values;
  values.reserve(node.size());
  for (std::size_t i = 0; i < node.size(); ++i) {
    Expected<double> v = ToDouble(node[i], file, key + "[" + std::to_string(i) + "]");
    if (!v) return v.status();
    values.push_back(*v);
  }
  return values;
}

Expected<Eigen::MatrixXd> ToNestedMatrix(const YAML::Node& node, const std::string& file,
                                         const std::string& key, int rows, int cols) {
  const std::string shape = ShapeText(rows, cols);
  if (!node.IsSequence() || static_cast<int>(node.size()) != rows) {
    return ParseError(Where(file, node) + ": " + key + " must be a " + shape +
                      " matrix written as a list of " + std::to_string(rows) + " rows");
  }
  Eigen::MatrixXd M(rows, cols);
  for (int r = 0; r < rows; ++r) {
    Expected<std::vector<double>> row =
        ToNumbers(node[r], file, key + "[" + std::to_string(r) + "]");
    if (!row) return row.status();
    if (static_cast<int>(row->size()) != cols) {
      return ParseError(Where(file, node[r]) + ": " + key + " row " + std::to_string(r) + " has " +
                        std::to_string(row->size()) + " values, expected " + std::to_string(cols) +
                        " (a " + shape + " matrix)");
    }
    for (int c = 0; c < cols; ++c)
      M(r, c) = (*row)[c];
  }
  return M;
}

Expected<RosMatrix> ToRosMatrix(const YAML::Node& node, const std::string& file,
                                const std::string& key) {
  RosMatrix m;
  m.where = Where(file, node);
  if (!node.IsMap()) {
    return ParseError(m.where + ": " + key + " must be a matrix {rows: R, cols: C, data: [...]}");
  }
  const std::string hint = "part of the {rows, cols, data} matrix " + key;
  Expected<YAML::Node> rows = Child(node, "rows", m.where + ": " + key, hint);
  if (!rows) return rows.status();
  Expected<YAML::Node> cols = Child(node, "cols", m.where + ": " + key, hint);
  if (!cols) return cols.status();
  Expected<YAML::Node> data = Child(node, "data", m.where + ": " + key, hint);
  if (!data) return data.status();
  Expected<int> r = ToInt(*rows, file, key + ".rows");
  if (!r) return r.status();
  Expected<int> c = ToInt(*cols, file, key + ".cols");
  if (!c) return c.status();
  Expected<std::vector<double>> values = ToNumbers(*data, file, key + ".data");
  if (!values) return values.status();
  m.rows = *r;
  m.cols = *c;
  m.data = std::move(*values);
  return m;
}

Expected<Eigen::MatrixXd> CheckedRosMatrix(const RosMatrix& m, const std::string& key, int rows,
                                           int cols) {
  if (m.rows <= 0 || m.cols <= 0) {
    return ParseError(m.where + ": " + key + " declares a " + ShapeText(m.rows, m.cols) +
                      " matrix; rows and cols must be positive");
  }
  const std::size_t declared = static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.cols);
  if (declared != m.data.size()) {
    std::string fix = "make rows x cols match the data";
    if (m.data.size() % static_cast<std::size_t>(m.rows) == 0) {
      fix = "if the data are right, set cols: " +
            std::to_string(m.data.size() / static_cast<std::size_t>(m.rows)) +
            "; otherwise correct the data";
    }
    return ParseError(m.where + ": " + key + " declares rows x cols = " +
                      ShapeText(m.rows, m.cols) + " = " + std::to_string(declared) +
                      " values but its data lists " + std::to_string(m.data.size()) + "; " + fix);
  }
  if (m.rows != rows || m.cols != cols) {
    return ParseError(m.where + ": " + key + " must be " + ShapeText(rows, cols) +
                      ", the file declares " + ShapeText(m.rows, m.cols));
  }
  Eigen::MatrixXd M(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j)
      M(i, j) = m.data[static_cast<std::size_t>(i * cols + j)];
  }
  return M;
}

}  // namespace aavio::io::yaml
