#pragma once
/// Splitting and parsing the lines of the text formats (events, IMU, trajectories): fields
/// separated by spaces, tabs or commas (a '\r' of Windows line ends too), '#' comment lines.

#include <array>
#include <charconv>
#include <cstddef>
#include <string_view>

namespace aavio::io::text {

inline bool IsSeparator(char c) {
  return c == ' ' || c == '\t' || c == ',' || c == '\r';
}

/// Blank, or a comment ('#' first after any separators).
inline bool IsSkipped(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && IsSeparator(line[i]))
    ++i;
  return i == line.size() || line[i] == '#';
}

/// Splits a line into at most N fields; returns the number of fields found.
template <std::size_t N>
std::size_t SplitFields(std::string_view line, std::array<std::string_view, N>* fields) {
  std::size_t count = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSeparator(line[i]))
      ++i;
    if (i == line.size()) break;
    std::size_t j = i;
    while (j < line.size() && !IsSeparator(line[j]))
      ++j;
    if (count < N) (*fields)[count] = line.substr(i, j - i);
    ++count;
    i = j;
  }
  return count;
}

/// The lines of a text, one by one, with their 1-based numbers (for "file:line" messages).
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  /// The next line (without its '\n'); false at the end.
  bool Next(std::string_view* line) {
    if (begin_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', begin_);
    if (end == std::string_view::npos) end = text_.size();
    *line = text_.substr(begin_, end - begin_);
    begin_ = end + 1;
    ++number_;
    return true;
  }
  std::size_t number() const { return number_; }  ///< of the line Next gave last

 private:
  std::string_view text_;
  std::size_t begin_ = 0, number_ = 0;
};

/// The whole field as a number of type T.
template <typename T>
bool ParseNumber(std::string_view text, T* value) {
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), *value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

}  // namespace aavio::io::text
