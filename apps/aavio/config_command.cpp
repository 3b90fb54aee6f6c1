// `aavio config`: prints (or writes) the effective configuration, or lists every key.
#include <CLI/CLI.hpp>
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
      ctx.out << std::left << std::setw(52) << key << " " << std::setw(14) << text << " "
              << index.fields[key].type << "\n";
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
  sub->add_flag("--list", options->list, "List every key with its value and type");
  sub->callback(
      [&ctx, options] { ctx.action = [&ctx, options] { return RunConfig(*options, ctx); }; });
}

}  // namespace aavio::cli
