#pragma once
/// Reading values from YAML with errors that name the file, the line, the key and the fix.
/// Internal to the io module (yaml-cpp stays out of every other module's headers).

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "aavio/common/status.hpp"

namespace aavio::io::yaml {

/// Parses a file. Missing files, unreadable files and syntax errors (with line:column) are
/// reported against `path`.
Expected<YAML::Node> LoadFile(const std::string& path);
/// Parses text; `origin` names it in messages.
Expected<YAML::Node> LoadText(const std::string& text, const std::string& origin);

/// "file:line" of a node (1-based line), or just "file" when the node has no position.
std::string Where(const std::string& file, const YAML::Node& node);

/// A required child `key` of the map `parent`, or NotFound naming `hint` (what the key holds).
Expected<YAML::Node> Child(const YAML::Node& parent, const std::string& key,
                           const std::string& file, const std::string& hint);

Expected<double> ToDouble(const YAML::Node& node, const std::string& file, const std::string& key);
Expected<int> ToInt(const YAML::Node& node, const std::string& file, const std::string& key);
Expected<std::string> ToString(const YAML::Node& node, const std::string& file,
                               const std::string& key);
/// A flat sequence of numbers.
Expected<std::vector<double>> ToNumbers(const YAML::Node& node, const std::string& file,
                                        const std::string& key);
/// A nested-list matrix [[a, b], [c, d]] of the given shape (DSEC style).
Expected<Eigen::MatrixXd> ToNestedMatrix(const YAML::Node& node, const std::string& file,
                                         const std::string& key, int rows, int cols);

/// A ROS camera_info style matrix {rows: R, cols: C, data: [...]}, as declared in the file.
struct RosMatrix {
  int rows = 0;
  int cols = 0;
  std::vector<double> data;  ///< row-major, as listed (its size is NOT checked against rows×cols)
  std::string where;         ///< "file:line" of the matrix
};
Expected<RosMatrix> ToRosMatrix(const YAML::Node& node, const std::string& file,
                                const std::string& key);
/// Checks the declared shape against `rows`×`cols` and the data length against the declaration,
/// then returns the matrix. Messages say how to fix the file.
Expected<Eigen::MatrixXd> CheckedRosMatrix(const RosMatrix& m, const std::string& key, int rows,
                                           int cols);

}  // namespace aavio::io::yaml
