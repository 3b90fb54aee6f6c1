// `aavio simulate`: a stereo event camera + IMU sequence with exact ground truth
// (docs/simulator.md).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <ostream>
#include <sstream>
#include <utility>
#include <vector>

#include "aavio/common/format.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/sim/presets.hpp"
#include "aavio/sim/sensor_model.hpp"
#include "aavio/sim/simulator.hpp"
#include "cli.hpp"
#include "option_checks.hpp"

namespace aavio::cli {

namespace {

int PrintSensor(const sim::SimulationRequest& request, Context& ctx) {
  Expected<sim::SimulationPreset> preset = sim::GetSimulationPreset(request.preset);
  Expected<sim::SensorModel> sensor =
      preset ? sim::MakeSensorModel(*preset, request.sensor, request.effects)
             : Expected<sim::SensorModel>(preset.status());
  if (!sensor) {
    ctx.err << "aavio simulate: error: " << sensor.status().message() << "\n";
    return kExitError;
  }
  ctx.out << io::FormatConfigYaml(FlattenConfig(*sensor),
                                  "sensor '" + sensor->name + "' of the " + request.preset +
                                      " preset (aavio simulate --sensor FILE reads this form)");
  return kExitOk;
}

// The options that disturb a stretch of the sequence on purpose.
struct DisturbanceOption {
  const char* name;
  sim::Disturbance::Kind kind;
  const char* help;
};
constexpr DisturbanceOption kDisturbanceOptions[] = {
    {"--dark", sim::Disturbance::Kind::kDark,
     "No events from either camera for SECONDS from START (repeatable): tracking loss"},
    {"--right-off", sim::Disturbance::Kind::kRightOff,
     "The right camera sends nothing for SECONDS from START (repeatable)"},
    {"--fast", sim::Disturbance::Kind::kFastMotion,
     "The camera moves up to FACTOR (default 4) times faster for SECONDS from START, speeding "
     "up and slowing down over a quarter of it each (repeatable)"},
    {"--stop", sim::Disturbance::Kind::kStop,
     "The camera slows to a standstill over the first quarter of SECONDS from START, stands "
     "still for half of it and starts again (a car at a red light; repeatable)"},
};

// "START:SECONDS", or for fast motion "START:SECONDS[:FACTOR]", in seconds of data.
Expected<sim::Disturbance> ParseDisturbance(const DisturbanceOption& option,
                                            const std::string& text) {
  const bool fast = option.kind == sim::Disturbance::Kind::kFastMotion;
  std::vector<double> numbers;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ':')) {
    double value = 0.0;
    if (!CLI::detail::lexical_cast(part, value) || !std::isfinite(value)) {
      numbers.clear();
      break;
    }
    numbers.push_back(value);
  }
  if (numbers.size() < 2 || numbers.size() > (fast ? 3u : 2u)) {
    return InvalidArgument(std::string(option.name) + " " + text + ": expected " +
                           (fast ? "START:SECONDS[:FACTOR]" : "START:SECONDS") +
                           " in seconds of data, e.g. 2:0.5");
  }
  sim::Disturbance d;
  d.kind = option.kind;
  d.start_s = numbers[0];
  d.duration_s = numbers[1];
  if (numbers.size() == 3) d.factor = numbers[2];
  // The ranges the simulation validates, said in the option's terms.
  const std::string what = std::string(option.name) + " " + text + ": ";
  if (d.start_s < 0.0) return InvalidArgument(what + "START must not be negative");
  if (d.duration_s < 1e-3 || d.duration_s > 86400.0)
    return InvalidArgument(what + "SECONDS must be in [0.001, 86400]");
  if (fast && (d.factor < 1.0 || d.factor > 20.0))
    return InvalidArgument(what + "FACTOR must be in [1, 20]");
  return d;
}

int RunSimulate(const sim::SimulationRequest& request, bool quiet_flag, Context& ctx) {
  // Progress only where someone watches it: on a terminal, and not with --quiet.
  const bool quiet = quiet_flag || !isatty(STDERR_FILENO);
  int last_percent = -1;
  auto progress = [&](double fraction) {
    const int percent = static_cast<int>(fraction * 100.0);
    if (quiet || percent == last_percent) return;
    last_percent = percent;
    ctx.err << "\rsimulating " << percent << " %" << std::flush;
  };
  Expected<sim::SimulationReport> report = sim::Simulate(request, progress);
  if (!quiet) ctx.err << "\r";
  if (!report) {
    ctx.err << "aavio simulate: error: " << report.status().message() << "\n";
    return kExitError;
  }
  const sim::SimulationReport& r = *report;
  ctx.out << StrFormat(
      "simulated %.2f s (%s) in %.1f s: %lld left + %lld right events (%.3f Mev/s per camera, "
      "%.1f %% noise, %lld dropped by the readout), %lld render steps, %lld IMU samples, %lld "
      "depth maps\n"
      "events per pixel per second (left): median %.2f, 99th percentile %.2f\n",
      r.duration_s, (request.preset + ", sensor " + r.sensor).c_str(), r.wall_s,
      static_cast<long long>(r.events_left), static_cast<long long>(r.events_right),
      r.mean_rate_ev_s * 1e-6,
      100.0 * static_cast<double>(r.noise_events) /
          std::max<double>(1.0, static_cast<double>(r.events_left + r.events_right)),
      static_cast<long long>(r.dropped_events), static_cast<long long>(r.render_steps),
      static_cast<long long>(r.imu_samples), static_cast<long long>(r.depth_maps),
      r.pixel_rate_median_hz, r.pixel_rate_p99_hz);
  if (!request.world_effects.empty()) ctx.out << "world effects: " << r.world_effects << "\n";
  if (!request.trajectory.empty()) {
    ctx.out << "recorded path: " << r.path_smoothing << "\n";
    ctx.out << "body to camera: " << r.body_to_camera << "\n";
  }
  ctx.out << "wrote " << r.sequence_yaml << "\n";
  return kExitOk;
}

}  // namespace

void RegisterSimulate(CLI::App& app, Context& ctx) {
  auto request = std::make_shared<sim::SimulationRequest>();
  auto quiet = std::make_shared<bool>(false);
  auto duration = std::make_shared<double>(0.0);
  auto baseline = std::make_shared<double>(0.0);
  auto print_sensor = std::make_shared<bool>(false);
  std::string names;
  for (const std::string& n : sim::SimulationPresetNames())
    names += (names.empty() ? "" : ", ") + n;
  CLI::App* sub = app.add_subcommand(
      "simulate", "Simulate a stereo event camera + IMU sequence with exact ground truth");
  sub->add_option("--preset", request->preset, "Sensor, scene and motion: " + names);
  sub->add_option("--out", request->out_dir, "Output folder (a sequence)");
  sub->add_flag("--overwrite", request->overwrite,
                "Replace a sequence already in --out (else that is an error)");
  sub->add_option("--format", request->format, "Event files: h5 (DSEC layout), bag or txt")
      ->check(CLI::IsMember({"h5", "bag", "txt"}));
  sub->add_option("--duration", *duration, "Seconds to simulate (default: the preset's)")
      ->check(NumberIn(1e-3, 86400.0));
  sub->add_option("--start", request->start_s, "Seconds to skip into --trajectory")
      ->check(DataSeconds());
  sub->add_option("--scene", request->scene,
                  "Another preset's scene: room, office, lab, hall, street or planes");
  sub->add_option("--motion", request->motion,
                  "Another preset's motion: hand_held, driving, drone or sinusoid");
  sub->add_option("--speed", request->speed,
                  "The motion played FACTOR times as fast (0.05-10; 0.2: slow, 3: fast)")
      ->check(NumberIn(0.05, 10.0));
  sub->add_option("--contrast", request->texture_contrast,
                  "The scene's texture contrast times FACTOR (0.2-3; 0.3: faint, 2: bold)")
      ->check(NumberIn(0.2, 3.0));
  sub->add_option("--rest", request->rest_at_start_s,
                  "The camera stands still for the first SECONDS, then speeds up into its motion "
                  "over half as long (a start at rest)")
      ->check(NumberIn(0.0, 3600.0));
  sub->add_option("--seed", request->seed, "Seed of the scene, motion, noise and sensor")
      ->check(Seed());
  sub->add_option("--trajectory", request->trajectory,
                  "Follow a recorded camera path (TUM file): a twin of a real sequence");
  sub->add_option("--calib", request->calibration, "Calibration replacing the preset's");
  sub->add_option("--baseline", *baseline,
                  "Stereo baseline in metres replacing the preset's (or --calib's): the right "
                  "camera moved along it (0.01-2)")
      ->check(NumberIn(0.01, 2.0));
  sub->add_option("--body-to-camera", request->body_to_camera,
                  "identity, driving (camera +z along travel, +y down) or auto")
      ->check(CLI::IsMember({"identity", "driving", "auto"}));
  std::string effect_names;
  for (const sim::SensorEffect& e : sim::SensorEffects())
    effect_names += (effect_names.empty() ? "" : ", ") + std::string(e.name);
  sub->add_option("--sensor", request->sensor,
                  "Sensor model: ideal, typical (default), harsh, or a YAML file of your sensor "
                  "(on top of typical; --print-sensor shows the keys)");
  sub->add_option(
         "--effects", request->effects,
         "Only these effects of the sensor, the rest ideal (comma-separated): " + effect_names)
      ->delimiter(',');
  std::string world_effect_names;
  for (const sim::WorldEffect& e : sim::WorldEffects())
    world_effect_names +=
        (world_effect_names.empty() ? "" : "; ") + std::string(e.name) + ": " + e.description;
  sub->add_option(
         "--world-effects", request->world_effects,
         "What the world adds to a static, steady scene (comma-separated): " + world_effect_names)
      ->delimiter(',');
  auto disturbances = std::make_shared<std::vector<std::pair<DisturbanceOption, std::string>>>();
  for (const DisturbanceOption& option : kDisturbanceOptions) {
    sub->add_option_function<std::vector<std::string>>(
           option.name,
           [disturbances, option](const std::vector<std::string>& values) {
             for (const std::string& v : values)
               disturbances->emplace_back(option, v);
           },
           option.help)
        ->type_name(option.kind == sim::Disturbance::Kind::kFastMotion ? "START:SECONDS[:FACTOR]"
                                                                       : "START:SECONDS");
  }
  sub->add_flag("--print-sensor", *print_sensor,
                "Print the sensor model as YAML (for a sensor file) and exit");
  sub->add_flag("--preview", request->preview,
                "Write preview/ PNGs (event frames, depth, top view)");
  sub->add_flag("--quiet", *quiet, "No progress output");
  sub->callback([&ctx, request, quiet, duration, baseline, print_sensor, disturbances] {
    ctx.action = [&ctx, request, quiet, duration, baseline, print_sensor, disturbances] {
      for (const auto& [option, text] : *disturbances) {
        Expected<sim::Disturbance> d = ParseDisturbance(option, text);
        if (!d) {
          ctx.err << "aavio simulate: error: " << d.status().message() << "\n";
          return static_cast<int>(kExitUsage);
        }
        request->disturbances.push_back(*d);
      }
      if (*print_sensor) return PrintSensor(*request, ctx);
      if (request->out_dir.empty()) {
        ctx.err << "aavio simulate: error: --out is required (the folder the sequence is written "
                   "to)\n";
        return static_cast<int>(kExitUsage);
      }
      if (*duration > 0.0) request->duration_s = *duration;
      if (*baseline > 0.0) request->baseline_m = *baseline;
      // Every field of the request comes from an option: a value it refuses is a wrong argument.
      if (const Status valid = request->Validate(); !valid.ok()) {
        ctx.err << "aavio simulate: error: " << valid.message() << "\n";
        return static_cast<int>(kExitUsage);
      }
      return RunSimulate(*request, *quiet, ctx);
    };
  });
}

}  // namespace aavio::cli
