#include "aavio/config/config_sources.hpp"

#include <algorithm>
#include <filesystem>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/presets.hpp"

namespace aavio::config {

namespace {

// A configuration file's entries: those of its small_sensor section apply (without that prefix)
// only on a small sensor, after the others.
Status ApplyFileEntries(std::vector<ConfigEntry> entries, const ConfigSources& sources,
                        pipeline::OdometryConfig* config) {
  const std::string prefix = std::string(pipeline::kSmallSensorSection) + ".";
  std::vector<ConfigEntry> small_sensor;
  std::erase_if(entries, [&](ConfigEntry& e) {
    if (!e.key.starts_with(prefix)) return false;
    e.key.erase(0, prefix.size());
    small_sensor.push_back(std::move(e));
    return true;
  });
  AAVIO_RETURN_IF_ERROR(ApplyConfigEntries(entries, config));
  if (!sources.sensor || !sources.sensor->small()) return Status::Ok();
  return ApplyConfigEntries(small_sensor, config);
}

// A shipped overlay by its name.
Status ApplyOverlay(const std::string& name, const ConfigSources& sources,
                    pipeline::OdometryConfig* config) {
  Expected<std::vector<ConfigEntry>> entries = io::OverlayEntries(name);
  if (!entries) return entries.status();
  return ApplyFileEntries(std::move(*entries), sources, config);
}

// Applies the preset, the files, the overlays and the --set overrides onto `config`.
Status ApplySources(const ConfigSources& sources, pipeline::OdometryConfig* config) {
  if (!sources.preset.empty()) {
    Expected<std::vector<ConfigEntry>> entries = io::PresetEntries(sources.preset);
    if (!entries) return entries.status();
    AAVIO_RETURN_IF_ERROR(ApplyFileEntries(std::move(*entries), sources, config));
  }
  const std::vector<std::string> overlays = io::OverlayNames();
  for (const std::string& file : sources.files) {
    // A shipped overlay's name, unless a file of that name is here (a folder of that name, such
    // as a run's output, is not a configuration file).
    const bool overlay = std::find(overlays.begin(), overlays.end(), file) != overlays.end() &&
                         !std::filesystem::is_regular_file(file);
    if (overlay) {
      AAVIO_RETURN_IF_ERROR(ApplyOverlay(file, sources, config));
      continue;
    }
    Expected<std::vector<ConfigEntry>> entries = io::ReadConfigYaml(file);
    if (!entries) return entries.status();
    AAVIO_RETURN_IF_ERROR(ApplyFileEntries(std::move(*entries), sources, config));
  }
  for (const std::string& name : sources.overlays)
    AAVIO_RETURN_IF_ERROR(ApplyOverlay(name, sources, config));
  std::vector<ConfigEntry> overrides;
  for (const std::string& text : sources.overrides) {
    Expected<ConfigEntry> entry = ParseKeyValueOverride(text);
    if (!entry) return entry.status();
    overrides.push_back(*entry);
  }
  return ApplyConfigEntries(overrides, config);
}

}  // namespace

std::string ConfigureForRig(const geometry::StereoRig& rig, ConfigSources* sources,
                            const std::optional<pipeline::SceneDepth>& scene) {
  sources->sensor = pipeline::SensorFacts::Of(rig);
  if (!sources->preset.empty()) return "";
  const pipeline::PresetSuggestion suggestion = pipeline::SuggestPreset(*sources->sensor);
  sources->preset = suggestion.name;
  if (!scene) return suggestion.reason;
  const std::string seen = StrFormat("median %.1f m of %zu edges %.1f s into the data",
                                     scene->median_m(), scene->depths_m.size(), scene->at_s);
  if (suggestion.name != "driving") return suggestion.reason + "; the scene " + seen;
  // Which preset's depth range holds more of the scene, from the presets themselves.
  auto range_of = [](const char* preset, double* near_m, double* far_m) {
    ConfigSources named;
    named.preset = preset;
    pipeline::OdometryConfig config;
    if (!ApplySources(named, &config).ok()) return false;
    *near_m = 1.0 / config.mapping.inv_depth_max;
    *far_m = 1.0 / config.mapping.inv_depth_min;
    return true;
  };
  double indoor_near = 0, indoor_far = 0, driving_near = 0, driving_far = 0;
  if (!range_of("indoor", &indoor_near, &indoor_far) ||
      !range_of("driving", &driving_near, &driving_far))
    return suggestion.reason;
  const double indoor = scene->ShareWithin(indoor_near, indoor_far);
  const double driving = scene->ShareWithin(driving_near, driving_far);
  const std::string shares = StrFormat(
      "%.0f %% of the scene's edges within the indoor preset's %g-%g m, %.0f %% within the "
      "driving preset's %g-%g m (%s)",
      100 * indoor, indoor_near, indoor_far, 100 * driving, driving_near, driving_far,
      seen.c_str());
  if (indoor <= driving) return suggestion.reason + "; " + shares;
  sources->preset = "indoor";
  return StrFormat("baseline %.2f m is a car's, but ", sources->sensor->baseline_m) + shares;
}

Expected<std::vector<pipeline::SensorSetting>> SensorSettingsOf(const ConfigSources& sources) {
  if (!sources.sensor) return std::vector<pipeline::SensorSetting>{};
  // The scene the later sources make (its depth range): defaults + sources, without the sensor.
  pipeline::OdometryConfig scene;
  AAVIO_RETURN_IF_ERROR(ApplySources(sources, &scene));
  return pipeline::DeriveSensorSettings(*sources.sensor, scene);
}

Expected<pipeline::OdometryConfig> ResolveOdometryConfig(const ConfigSources& sources) {
  Expected<std::vector<pipeline::SensorSetting>> derived = SensorSettingsOf(sources);
  if (!derived) return derived.status();
  pipeline::OdometryConfig config;
  AAVIO_RETURN_IF_ERROR(ApplyConfigEntries(pipeline::ToConfigEntries(*derived), &config));
  AAVIO_RETURN_IF_ERROR(ApplySources(sources, &config));
  Status status = config.Validate();
  if (!status.ok()) return InvalidArgument("invalid configuration: " + status.message());
  return config;
}

std::string DescribeSources(const ConfigSources& sources) {
  std::string text = sources.preset.empty() ? "defaults" : "preset " + sources.preset;
  if (sources.sensor) text = "the sensor's settings + " + text;
  for (const std::string& file : sources.files)
    text += " + " + file;
  for (const std::string& name : sources.overlays)
    text += " + " + name;
  for (const std::string& o : sources.overrides)
    text += " + --set " + o;
  return text;
}

}  // namespace aavio::config
