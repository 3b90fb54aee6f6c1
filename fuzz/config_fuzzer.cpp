// Configuration text: a config YAML applied to the odometry's parameters and validated, a
// sequence.yaml, and each line as a `--set KEY=VALUE` override.
#include <string>
#include <vector>

#include "aavio/common/config_fields.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/pipeline/odometry_config.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (auto entries = io::ParseConfigYaml(text, "config.yaml")) {
    pipeline::OdometryConfig config;
    if (ApplyConfigEntries(*entries, &config).ok()) (void)config.Validate();
  }
  (void)io::ReadSequenceYaml(fuzz::WriteInput("sequence.yaml", data, size));
  std::vector<ConfigEntry> overrides;
  std::size_t begin = 0;
  for (int line = 0; line < 64 && begin <= text.size(); ++line) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    if (auto entry = ParseKeyValueOverride(std::string_view(text).substr(begin, end - begin))) {
      overrides.push_back(std::move(*entry));
    }
    begin = end + 1;
  }
  pipeline::OdometryConfig config;
  if (ApplyConfigEntries(overrides, &config).ok()) (void)config.Validate();
  return 0;
}
