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

// The header of a configuration made for a rig: the sensor, the preset and every sensor rule's
// value with its rule (a source that sets one instead is named).
std::string RigHeader(const config::ConfigSources& sources, const std::string& preset_reason,
                      const config::ResolvedConfig& resolved) {
  std::string text = "sensor: " + sources.sensor->Describe() + "\n";
  text += "preset: " + sources.preset +
          (preset_reason.empty() ? " (named)" : " (" + preset_reason + ")") + "\n";
  text += "derived from the sensor:\n";
  pipeline::OdometryConfig copy = resolved.config;
  auto index = BuildFieldIndex(copy);
  for (const config::SensorRuling& s : resolved.sensor_rulings) {
    const std::string instead = s.applied ? ""
                                          : " [" + resolved.origin.at(s.key) + " sets " +
                                                index.fields.at(s.key).get().scalar + "]";
    text += StrFormat("  %-44s %-6s %s%s\n", s.key.c_str(), s.value.c_str(), s.rule.c_str(),
                      instead.c_str());
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
  Expected<config::ResolvedConfig> resolved = config::Resolve(options.sources);
  if (!resolved) {
    ctx.err << "aavio config: error: " << resolved.status().message() << "\n";
    return ConfigErrorExitCode(options.sources);
  }
  const pipeline::OdometryConfig* config = &resolved->config;
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
      const auto origin = resolved->origin.find(key);
      if (origin != resolved->origin.end()) ctx.out << "    from " << origin->second << "\n";
    }
    return kExitOk;
  }
  std::string header = "aavio effective configuration (" + VersionString() +
                       ")\nfrom: " + config::DescribeSources(options.sources);
  if (options.sources.sensor)
    header +=
        "\nfor: " + options.for_path + "\n" + RigHeader(options.sources, preset_reason, *resolved);
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
