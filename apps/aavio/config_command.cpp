// `aavio config`: prints (or writes) the effective configuration, or lists every key.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iomanip>
#include <ostream>

#include "aavio/io/config_yaml.hpp"
#include "cli.hpp"
#include "config_resolution.hpp"

namespace aavio::cli {

namespace {

struct ConfigOptions {
  ConfigSources sources;
  std::string out_path;
  bool list = false;
};

// What Validate() requires of `key`, found by trying extreme values on a copy of `config`: each
// error that names the key says the rule ("must be in [0.1, 10000]"); "" when nothing is refused
// (bools, enumerations, lists, unbounded values).
std::string RuleOf(const pipeline::OdometryConfig& config, const std::string& key,
                   const std::string& type) {
  std::vector<std::string> probes;
  if (type == "integer") probes = {"-2147483648", "2147483647", "0"};
  if (type == "number") probes = {"-1e300", "1e300", "0"};
  std::vector<std::string> rules;
  for (const std::string& probe : probes) {
    pipeline::OdometryConfig copy = config;
    Expected<ConfigEntry> entry = ParseKeyValueOverride(key + "=" + probe);
    if (!entry || !ApplyConfigEntries({*entry}, &copy).ok()) continue;
    const Status status = copy.Validate();
    const std::string& message = status.message();
    if (status.ok() || !message.starts_with(key + " ")) continue;
    std::string rule = message.substr(key.size() + 1);
    if (rule.starts_with("= ")) {  // "= <the probed value> must ..."
      const std::size_t space = rule.find(' ', 2);
      rule = space == std::string::npos ? "" : rule.substr(space + 1);
    }
    if (!rule.empty() && std::find(rules.begin(), rules.end(), rule) == rules.end())
      rules.push_back(rule);
  }
  std::string text;
  for (const std::string& rule : rules)
    text += (text.empty() ? "" : "; ") + rule;
  return text;
}

int RunConfig(const ConfigOptions& options, Context& ctx) {
  Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(options.sources);
  if (!config) {
    ctx.err << "aavio config: error: " << config.status().message() << "\n";
    return kExitError;
  }
  if (options.list) {
    pipeline::OdometryConfig copy = *config;
    auto index = BuildFieldIndex(copy);
    for (const std::string& key : index.order) {
      const ConfigValue value = index.fields[key].get();
      std::string text = value.scalar;
      if (value.is_list) {
        text = "[";
        for (std::size_t i = 0; i < value.list.size(); ++i)
          text += (i ? ", " : "") + value.list[i];
        text += "]";
      }
      const config_detail::FieldRef& field = index.fields[key];
      const std::string rule = RuleOf(*config, key, field.type);
      ctx.out << std::left << std::setw(52) << key << " " << std::setw(14) << text << " "
              << field.type << (rule.empty() ? "" : ", " + rule) << "\n    " << field.doc << "\n";
    }
    return kExitOk;
  }
  const std::string yaml = io::FormatConfigYaml(
      FlattenConfig(*config), "aavio effective configuration (" + VersionString() +
                                  ")\nfrom: " + DescribeSources(options.sources));
  if (options.out_path.empty()) {
    ctx.out << yaml;
    return kExitOk;
  }
  Status status = io::WriteTextFile(options.out_path, yaml);
  if (!status.ok()) {
    ctx.err << "aavio config: error: " << status.message() << "\n";
    return kExitError;
  }
  ctx.out << "wrote " << options.out_path << "\n";
  return kExitOk;
}

}  // namespace

void RegisterConfig(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<ConfigOptions>();
  CLI::App* sub = app.add_subcommand(
      "config", "Print the effective parameters (defaults, preset, files, overrides)");
  AddConfigOptions(*sub, &options->sources);
  sub->add_option("--out", options->out_path, "Write the YAML here instead of printing it");
  sub->add_flag("--list", options->list,
                "List every key with its value, type, range and a description");
  sub->callback(
      [&ctx, options] { ctx.action = [&ctx, options] { return RunConfig(*options, ctx); }; });
}

}  // namespace aavio::cli
