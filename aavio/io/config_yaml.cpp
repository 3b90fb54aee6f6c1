#include "aavio/io/config_yaml.hpp"

#include <cstdio>
#include <sstream>

#include "aavio/io/yaml_reading.hpp"

namespace aavio::io {

namespace {

Status Flatten(const YAML::Node& node, const std::string& prefix, const std::string& origin,
               std::vector<ConfigEntry>* out) {
  for (const auto& item : node) {
    const std::string where = yaml::Where(origin, item.first);
    if (!item.first.IsScalar()) {
      return ParseError(where +
                        ": a key must be a name (e.g. max_iterations), not a list or a map");
    }
    const std::string key = prefix + item.first.Scalar();
    const YAML::Node& value = item.second;
    if (value.IsMap()) {
      AAVIO_RETURN_IF_ERROR(Flatten(value, key + ".", origin, out));
    } else if (value.IsSequence()) {
      ConfigEntry entry{key, {}};
      entry.value.is_list = true;
      entry.value.origin = where;
      for (const auto& element : value) {
        if (!element.IsScalar()) {
          return ParseError(where + ": " + key + " must be a flat list of values");
        }
        entry.value.list.push_back(element.Scalar());
      }
      out->push_back(std::move(entry));
    } else if (value.IsScalar()) {
      out->push_back({key, {value.Scalar(), {}, false, where}});
    } else {
      return ParseError(where + ": " + key + " has no value");
    }
  }
  return Status::Ok();
}

bool NeedsQuotes(const std::string& s) {
  if (s.empty()) return true;
  for (char c : s) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '_' || c == '-' || c == '.' || c == '/' || c == '+';
    if (!plain) return true;
  }
  return false;
}

std::string Scalar(const std::string& s) {
  if (!NeedsQuotes(s)) return s;
  std::string quoted = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

std::vector<std::string> Split(const std::string& key) {
  std::vector<std::string> parts;
  std::stringstream stream(key);
  std::string part;
  while (std::getline(stream, part, '.'))
    parts.push_back(part);
  return parts;
}

}  // namespace

Expected<std::vector<ConfigEntry>> ParseConfigYaml(const std::string& text,
                                                   const std::string& origin) {
  Expected<YAML::Node> root = yaml::LoadText(text, origin);
  if (!root) return root.status();
  std::vector<ConfigEntry> entries;
  AAVIO_RETURN_IF_ERROR(Flatten(*root, "", origin, &entries));
  return entries;
}

Expected<std::vector<ConfigEntry>> ReadConfigYaml(const std::string& path) {
  Expected<YAML::Node> root = yaml::LoadFile(path);
  if (!root) return root.status();
  std::vector<ConfigEntry> entries;
  AAVIO_RETURN_IF_ERROR(Flatten(*root, "", path, &entries));
  return entries;
}

std::string FormatConfigYaml(const std::vector<ConfigEntry>& entries, const std::string& header) {
  std::string out;
  std::stringstream header_lines(header);
  std::string line;
  while (std::getline(header_lines, line))
    out += "# " + line + "\n";
  std::vector<std::string> open;  // the sections currently open
  for (const ConfigEntry& entry : entries) {
    std::vector<std::string> parts = Split(entry.key);
    const std::string leaf = parts.back();
    parts.pop_back();
    std::size_t common = 0;
    while (common < open.size() && common < parts.size() && open[common] == parts[common]) {
      ++common;
    }
    open.resize(common);
    for (std::size_t i = common; i < parts.size(); ++i) {
      if (i == 0 && !out.empty()) out += "\n";
      out += std::string(2 * i, ' ') + parts[i] + ":\n";
      open.push_back(parts[i]);
    }
    out += std::string(2 * parts.size(), ' ') + leaf + ": ";
    if (entry.value.is_list) {
      out += "[";
      for (std::size_t i = 0; i < entry.value.list.size(); ++i) {
        out += (i ? ", " : "") + Scalar(entry.value.list[i]);
      }
      out += "]\n";
    } else {
      out += Scalar(entry.value.scalar) + "\n";
    }
  }
  return out;
}

Status WriteTextFile(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return IoError(path + ": cannot open for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  const bool closed = std::fclose(file) == 0;
  if (!ok || !closed) return IoError(path + ": write failed (disk full?)");
  return Status::Ok();
}

}  // namespace aavio::io
