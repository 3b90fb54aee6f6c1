// `aavio config`: prints (or writes) the effective configuration, or lists every key.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iomanip>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/config/scene_measurement.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/sequence.hpp"
#include "cli.hpp"
#include "config_options.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {

namespace {

struct ConfigOptions {
  config::ConfigSources sources;
  std::string for_path;
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

// The calibration at `path`, or the one the sequence at `path` names.
Expected<io::LoadedCalibration> CalibrationOf(const std::string& path) {
  Expected<io::LoadedCalibration> calibration = io::LoadCalibration(path);
  if (calibration) return calibration;
  Expected<io::SequenceDescription> sequence = io::DescribeSequence(path, "");
  if (!sequence) {
    return InvalidArgument("--for " + path + ": neither a calibration (" +
                           calibration.status().message() + ") nor a sequence (" +
                           sequence.status().message() + ")");
  }
  if (sequence->calibration.empty())
    return InvalidArgument("--for " + path + ": the sequence names no calibration");
  return io::LoadCalibration(sequence->calibration);
}

// The header of a configuration made for a rig: the sensor, the preset and every derived value
// with its rule (a later source that changes one is named).
Expected<std::string> RigHeader(const config::ConfigSources& sources,
                                const std::string& preset_reason,
                                const pipeline::OdometryConfig& config) {
  Expected<std::vector<pipeline::SensorSetting>> derived = config::SensorSettingsOf(sources);
  if (!derived) return derived.status();
  std::string text = "sensor: " + sources.sensor->Describe() + "\n";
  text += "preset: " + sources.preset +
          (preset_reason.empty() ? " (named)" : " (" + preset_reason + ")") + "\n";
  text += "derived from the sensor:\n";
  pipeline::OdometryConfig copy = config;
  auto index = BuildFieldIndex(copy);
  for (const pipeline::SensorSetting& s : *derived) {
    const std::string now = index.fields.at(s.key).get().scalar;
    double a = 0.0, b = 0.0;
    const bool kept = now == s.value || (config_detail::ParseDouble(now, &a).ok() &&
                                         config_detail::ParseDouble(s.value, &b).ok() && a == b);
    text += StrFormat("  %-44s %-6s %s%s\n", s.key.c_str(), s.value.c_str(), s.rule.c_str(),
                      kept ? "" : (" [a later source sets " + now + "]").c_str());
  }
  return text;
}

int RunConfig(ConfigOptions options, Context& ctx) {
  std::string preset_reason;
  if (!options.for_path.empty()) {
    Expected<io::LoadedCalibration> calibration = CalibrationOf(options.for_path);
    if (!calibration) {
      ctx.err << "aavio config: error: " << calibration.status().message() << "\n";
      return kExitError;
    }
    for (const std::string& warning : calibration->warnings)
      ctx.err << "warning: " << warning << "\n";
    // A sequence's first moments show how far its scene is, for the preset.
    if (options.sources.preset.empty() && !io::LoadCalibration(options.for_path).ok()) {
      Expected<OpenedSequence> opened = OpenSequence(options.for_path, "");
      Expected<std::string> why =
          opened ? config::ConfigureForSequence(opened->reader.get(), calibration->rig,
                                                opened->reader->start_ns(),
                                                opened->reader->end_ns(), &options.sources)
                 : Expected<std::string>(opened.status());
      if (!why) {
        ctx.err << "aavio config: error: " << why.status().message() << "\n";
        return kExitError;
      }
      preset_reason = *why;
    } else {
      preset_reason = config::ConfigureForRig(calibration->rig, &options.sources);
    }
  }
  Expected<pipeline::OdometryConfig> config = config::ResolveOdometryConfig(options.sources);
  if (!config) {
    ctx.err << "aavio config: error: " << config.status().message() << "\n";
    return ConfigErrorExitCode(options.sources);
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
  std::string header = "aavio effective configuration (" + VersionString() +
                       ")\nfrom: " + config::DescribeSources(options.sources);
  if (options.sources.sensor) {
    Expected<std::string> rig_header = RigHeader(options.sources, preset_reason, *config);
    if (!rig_header) {
      ctx.err << "aavio config: error: " << rig_header.status().message() << "\n";
      return kExitError;
    }
    header += "\nfor: " + options.for_path + "\n" + *rig_header;
  }
  const std::string yaml = io::FormatConfigYaml(FlattenConfig(*config), header);
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
      "config",
      "Print the effective parameters (defaults, the sensor's, preset, files, overrides)");
  AddConfigOptions(*sub, &options->sources);
  sub->add_option("--for", options->for_path,
                  "A sequence or calibration: derive the sensor's settings from its rig, pick "
                  "the preset it suggests unless --preset names one, and say why")
      ->type_name("PATH");
  sub->add_option("--out", options->out_path, "Write the YAML here instead of printing it");
  sub->add_flag("--list", options->list,
                "List every key with its value, type, range and a description");
  sub->callback(
      [&ctx, options] { ctx.action = [&ctx, options] { return RunConfig(*options, ctx); }; });
}

}  // namespace aavio::cli
