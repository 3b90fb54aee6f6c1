#include "aavio/config/config_sources.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

#include "aavio/common/format.hpp"
#include "aavio/config/presets.hpp"
#include "aavio/io/config_yaml.hpp"

namespace aavio::config {

namespace {

// The smallest disparity a depth is measured from: static stereo's sub-pixel refinement resolves
// about half a pixel, so a farther depth range only adds noise.
constexpr double kMinSceneDisparityPx = 0.5;

// A configuration file's entries: those of its small_sensor section count (without that prefix)
// only on a small sensor, after the others.
void AddFileEntries(std::vector<ConfigEntry> entries, const ConfigSources& sources,
                    std::vector<ConfigEntry>* out) {
  const std::string prefix = std::string(kSmallSensorSection) + ".";
  std::vector<ConfigEntry> small_sensor;
  std::erase_if(entries, [&](ConfigEntry& e) {
    if (!e.key.starts_with(prefix)) return false;
    e.key.erase(0, prefix.size());
    small_sensor.push_back(std::move(e));
    return true;
  });
  out->insert(out->end(), entries.begin(), entries.end());
  if (sources.sensor && sources.sensor->small())
    out->insert(out->end(), small_sensor.begin(), small_sensor.end());
}

// A shipped overlay by its name.
Status AddOverlay(const std::string& name, const ConfigSources& sources,
                  std::vector<ConfigEntry>* out) {
  Expected<std::vector<ConfigEntry>> entries = OverlayEntries(name);
  if (!entries) return entries.status();
  AddFileEntries(std::move(*entries), sources, out);
  return Status::Ok();
}

// The entries of the preset, the files, the overlays and the --set overrides, in that order
// (later wins).
Expected<std::vector<ConfigEntry>> EntriesOf(const ConfigSources& sources) {
  std::vector<ConfigEntry> out;
  if (!sources.preset.empty()) {
    Expected<std::vector<ConfigEntry>> entries = PresetEntries(sources.preset);
    if (!entries) return entries.status();
    AddFileEntries(std::move(*entries), sources, &out);
  }
  out.insert(out.end(), sources.scene.begin(), sources.scene.end());
  const std::vector<std::string> overlays = OverlayNames();
  for (const std::string& file : sources.files) {
    // A shipped overlay's name, unless a file of that name is here (a folder of that name, such
    // as a run's output, is not a configuration file).
    const bool overlay = std::find(overlays.begin(), overlays.end(), file) != overlays.end() &&
                         !std::filesystem::is_regular_file(file);
    if (overlay) {
      AAVIO_RETURN_IF_ERROR(AddOverlay(file, sources, &out));
      continue;
    }
    Expected<std::vector<ConfigEntry>> entries = io::ReadConfigYaml(file);
    if (!entries) return entries.status();
    AddFileEntries(std::move(*entries), sources, &out);
  }
  for (const std::string& name : sources.overlays)
    AAVIO_RETURN_IF_ERROR(AddOverlay(name, sources, &out));
  for (const std::string& text : sources.overrides) {
    Expected<ConfigEntry> entry = ParseKeyValueOverride(text);
    if (!entry) return entry.status();
    out.push_back(std::move(*entry));
  }
  return out;
}

// The depth range a preset gives.
bool PresetDepthRange(const char* preset, double* near_m, double* far_m) {
  ConfigSources named;
  named.preset = preset;
  Expected<pipeline::OdometryConfig> config = ResolveOdometryConfig(named);
  if (!config) return false;
  *near_m = 1.0 / config->mapping.inv_depth_max;
  *far_m = 1.0 / config->mapping.inv_depth_min;
  return true;
}

ConfigEntry SceneEntry(const char* key, double value, const std::string& why) {
  ConfigEntry e;
  e.key = key;
  e.value.scalar = StrFormat("%.6g", value);
  e.value.origin = "the measured scene (" + why + ")";
  return e;
}

// A rig that suggests the indoor preset, in a scene mostly beyond that preset's depth range:
// the range is widened to hold it (sources->scene), and why is returned ("" when it holds it).
std::string WidenDepthRangeToScene(const pipeline::SceneDepth& scene, const std::string& seen,
                                   ConfigSources* sources) {
  double near_m = 0, far_m = 0;
  if (!PresetDepthRange("indoor", &near_m, &far_m)) return "";
  const double share = scene.ShareWithin(near_m, far_m);
  if (share >= 0.5 || scene.depths_m.empty()) return "";
  const double p90_m = scene.depths_m[scene.depths_m.size() * 9 / 10];
  const double fb = sources->sensor->focal_px * sources->sensor->baseline_m;
  const double wide_far_m = std::min(2.0 * p90_m, fb / kMinSceneDisparityPx);
  if (!(wide_far_m > far_m)) return "";
  const double far_rounded_m = std::ceil(wide_far_m);
  const std::string why = StrFormat(
      "%.0f %% of its edges within the indoor preset's %g-%g m; %s; twice its 90th percentile "
      "%.1f m, at most %.1f px of disparity",
      100 * share, near_m, far_m, seen.c_str(), p90_m, kMinSceneDisparityPx);
  sources->scene = {SceneEntry("mapping.inv_depth_min", 1.0 / far_rounded_m, why),
                    SceneEntry("mapping.temporal_stereo.max_depth_m", far_rounded_m, why)};
  return StrFormat(
      "; the scene %s, %.0f %% of it within the preset's %g-%g m: depth range "
      "%g-%g m",
      seen.c_str(), 100 * share, near_m, far_m, near_m, far_rounded_m);
}

}  // namespace

std::string ConfigureForRig(const geometry::StereoRig& rig, ConfigSources* sources,
                            const std::optional<pipeline::SceneDepth>& scene) {
  sources->sensor = SensorFacts::Of(rig);
  if (!sources->preset.empty()) return "";
  const PresetSuggestion suggestion = SuggestPreset(*sources->sensor);
  sources->preset = suggestion.name;
  if (!scene) return suggestion.reason;
  const std::string seen = StrFormat("median %.1f m of %zu edges %.1f s into the data",
                                     scene->median_m(), scene->depths_m.size(), scene->at_s);
  if (suggestion.name != "driving") {
    const std::string widened = WidenDepthRangeToScene(*scene, seen, sources);
    return suggestion.reason + (widened.empty() ? "; the scene " + seen : widened);
  }
  // Which preset's depth range holds more of the scene, from the presets themselves.
  double indoor_near = 0, indoor_far = 0, driving_near = 0, driving_far = 0;
  if (!PresetDepthRange("indoor", &indoor_near, &indoor_far) ||
      !PresetDepthRange("driving", &driving_near, &driving_far))
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

Expected<ResolvedConfig> Resolve(const ConfigSources& sources) {
  Expected<std::vector<ConfigEntry>> entries = EntriesOf(sources);
  if (!entries) return entries.status();
  ResolvedConfig resolved;
  AAVIO_RETURN_IF_ERROR(ApplyConfigEntries(*entries, &resolved.config));
  std::set<std::string> set_by_sources;
  for (const ConfigEntry& e : *entries) {
    set_by_sources.insert(e.key);
    resolved.origin[e.key] = e.value.origin;
  }
  if (sources.sensor) {
    resolved.sensor_rulings = ApplySensorRules(*sources.sensor, set_by_sources, &resolved.config);
    for (const SensorRuling& r : resolved.sensor_rulings) {
      if (r.applied) resolved.origin[r.key] = "the sensor's rule (" + r.rule + ")";
    }
  }
  Status status = resolved.config.Validate();
  if (!status.ok()) return InvalidArgument("invalid configuration: " + status.message());
  return resolved;
}

Expected<pipeline::OdometryConfig> ResolveOdometryConfig(const ConfigSources& sources) {
  Expected<ResolvedConfig> resolved = Resolve(sources);
  if (!resolved) return resolved.status();
  return std::move(resolved->config);
}

std::string DescribeSources(const ConfigSources& sources) {
  std::string text = sources.preset.empty() ? "defaults" : "preset " + sources.preset;
  if (sources.sensor) text = "the sensor's settings + " + text;
  if (!sources.scene.empty()) text += " + the measured scene's depth range";
  for (const std::string& file : sources.files)
    text += " + " + file;
  for (const std::string& name : sources.overlays)
    text += " + " + name;
  for (const std::string& o : sources.overrides)
    text += " + --set " + o;
  return text;
}

}  // namespace aavio::config
