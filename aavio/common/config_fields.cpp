#include "aavio/common/config_fields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aavio {
namespace config_detail {

Status ParseBool(const std::string& text, bool* out) {
  static const std::array<std::string_view, 5> kTrue = {"true", "True", "TRUE", "yes", "on"};
  static const std::array<std::string_view, 5> kFalse = {"false", "False", "FALSE", "no", "off"};
  if (std::find(kTrue.begin(), kTrue.end(), text) != kTrue.end() || text == "1") {
    *out = true;
    return Status::Ok();
  }
  if (std::find(kFalse.begin(), kFalse.end(), text) != kFalse.end() || text == "0") {
    *out = false;
    return Status::Ok();
  }
  return InvalidArgument("expected true or false, got '" + text + "'");
}

Status ParseDouble(const std::string& text, double* out) {
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (begin != end && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, *out);
  if (ec != std::errc() || ptr != end || text.empty()) {
    return InvalidArgument("expected a number, got '" + text + "'");
  }
  if (!std::isfinite(*out)) return InvalidArgument("expected a finite number, got '" + text + "'");
  return Status::Ok();
}

Status ParseInt64(const std::string& text, std::int64_t* out) {
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (begin != end && *begin == '+') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, *out);
  if (ec == std::errc::result_out_of_range) {
    return InvalidArgument("integer '" + text + "' is out of range");
  }
  if (ec != std::errc() || ptr != end || text.empty()) {
    return InvalidArgument("expected an integer, got '" + text + "'");
  }
  return Status::Ok();
}

std::string FormatDouble(double value) {
  char buffer[64];
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, ptr);
  // Keep YAML readers from taking "2" as an integer where a float is meant: harmless either way,
  // but "2.0" documents the type.
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

namespace {

std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string_view LastSegment(std::string_view key) {
  const std::size_t dot = key.rfind('.');
  return dot == std::string_view::npos ? key : key.substr(dot + 1);
}

}  // namespace

std::string DidYouMean(const std::string& key, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const std::string& candidate : known) {
    // The full key catches typos; the last segment catches a right name in the wrong section.
    const std::size_t full = EditDistance(key, candidate);
    const std::size_t last = EditDistance(LastSegment(key), LastSegment(candidate)) +
                             (LastSegment(key) == LastSegment(candidate) ? 0 : 1);
    const std::size_t distance = std::min(full, last);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  const std::size_t tolerance = std::max<std::size_t>(2, LastSegment(key).size() / 3);
  return best_distance <= tolerance ? best : std::string();
}

}  // namespace config_detail

Expected<ConfigEntry> ParseKeyValueOverride(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0) {
    return InvalidArgument("override '" + std::string(text) +
                           "' is not of the form key=value (e.g. mapping.eta=0.1)");
  }
  auto trim = [](std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
      s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
      s.remove_suffix(1);
    return s;
  };
  ConfigEntry entry;
  entry.key = std::string(trim(text.substr(0, eq)));
  std::string_view value = trim(text.substr(eq + 1));
  entry.value.origin = "--set " + std::string(text);
  if (!value.empty() && value.front() == '[') {
    if (value.back() != ']') {
      return InvalidArgument("override '" + std::string(text) + "': list value must end with ']'");
    }
    entry.value.is_list = true;
    value = value.substr(1, value.size() - 2);
    while (!trim(value).empty()) {
      const std::size_t comma = value.find(',');
      entry.value.list.emplace_back(trim(value.substr(0, comma)));
      if (comma == std::string_view::npos) break;
      value.remove_prefix(comma + 1);
    }
  } else {
    if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'') &&
        value.back() == value.front()) {
      value = value.substr(1, value.size() - 2);
    }
    entry.value.scalar = std::string(value);
  }
  return entry;
}

std::string FieldChecker::Num(double value) {
  char buffer[64];
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, ptr);
}

FieldChecker& FieldChecker::Require(bool condition, const char* name, const std::string& message) {
  if (first_error_.ok() && !condition) {
    first_error_ = InvalidArgument(std::string(name) + " " + message);
  }
  return *this;
}

}  // namespace aavio
