// `aavio representations`: the representations of one tick of a sequence as PNGs — time
// surfaces, negative TS and gradients, the AA map with its blocks, and the edge samples (AA and,
// for comparison, ESVO's newest events at the same count).
#include <CLI/CLI.hpp>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/events/representation_builder.hpp"
#include "aavio/geometry/rectification.hpp"
#include "cli.hpp"
#include "config_options.hpp"
#include "option_checks.hpp"
#include "representation_images.hpp"
#include "sequence_opening.hpp"

namespace aavio::cli {
namespace {

struct RepresentationsOptions {
  std::string sequence;
  std::string calibration;
  std::string out_dir;
  double at_s = -1.0;
  double history_s = 0.3;
  config::ConfigSources config;
};

Status Run(RepresentationsOptions options, Context& ctx, int* exit_code) {
  Expected<OpenedSequence> opened = OpenSequence(options.sequence, options.calibration);
  if (!opened) return opened.status();
  config::ConfigureForRig(opened->calibration.rig, &options.config);
  Expected<pipeline::OdometryConfig> config = config::ResolveOdometryConfig(options.config);
  if (!config) {
    *exit_code = ConfigErrorExitCode(options.config);
    return config.status();
  }
  const geometry::StereoRig& rig = opened->calibration.rig;
  io::SequenceReader* reader = opened->reader.get();
  const TimeNs start = reader->start_ns(), end = reader->end_ns();
  const TimeNs at = start + SecondsToNs(options.at_s);
  if (options.at_s < 0.0 || at > end) {
    return InvalidArgument(StrFormat("--at %.3f is outside the sequence (0 to %.3f s)",
                                     options.at_s, NsToSeconds(end - start)));
  }
  const TimeNs from = std::max(start, at - SecondsToNs(options.history_s));
  AAVIO_RETURN_IF_ERROR(reader->Seek(from));

  const events::RepresentationConfig rc = pipeline::RepresentationConfigOf(*config);
  const geometry::StereoRectification rectification = geometry::BuildStereoRectification(rig);
  events::RepresentationBuilder builder(rectification, rig.width(), rig.height(), rc, from);
  std::vector<events::Event> recent_left;  // for ESVO's selection
  io::SensorPacket packet;
  std::int64_t left_events = 0, right_events = 0;
  while (true) {
    Expected<bool> more = reader->Next(&packet);
    if (!more) return more.status();
    if (!*more || packet.t_begin_ns > at) break;
    AAVIO_RETURN_IF_ERROR(builder.AddEvents(events::Camera::kLeft, packet.left));
    AAVIO_RETURN_IF_ERROR(builder.AddEvents(events::Camera::kRight, packet.right));
    left_events += static_cast<std::int64_t>(packet.left.size());
    right_events += static_cast<std::int64_t>(packet.right.size());
    for (const events::Event& e : packet.left) {
      if (e.t_ns > at - 50 * kNsPerMs && e.t_ns <= at) recent_left.push_back(e);
    }
  }
  events::Observation obs;
  AAVIO_RETURN_IF_ERROR(builder.Build(at, &obs));
  const std::vector<events::EdgeSample> esvo_samples = events::SelectNewestEventsAtCount(
      recent_left, at, rectification.left, rc.edge_sampling, obs.samples.size());

  Expected<std::vector<std::string>> written =
      WriteRepresentationImages(obs, esvo_samples, rc.adaptive_accumulation.grid_cols,
                                rc.adaptive_accumulation.grid_rows, options.out_dir);
  if (!written) return written.status();

  int closed = 0;
  for (const events::AaBlock& block : obs.aa_blocks)
    closed += block.closed ? 1 : 0;
  ctx.out << StrFormat(
      "tick at %.3f s (%s s on the sequence clock); events read from %.3f s: %lld left, %lld "
      "right\n"
      "AA: %lld events in the %.0f ms window, %lld accumulated; %d of %zu blocks froze\n"
      "samples: %zu from AA (budget %d); ESVO's newest events at the same count: %zu\n"
      "stage times [ms]: time surfaces %.2f, negative TS + gradients %.2f, AA %.2f, sampling "
      "%.2f\n",
      options.at_s, FormatSecondsNs(at).c_str(), NsToSeconds(from - start),
      static_cast<long long>(left_events), static_cast<long long>(right_events),
      static_cast<long long>(obs.aa_window_events), rc.adaptive_accumulation.window_ms,
      static_cast<long long>(obs.aa_used_events), closed, obs.aa_blocks.size(), obs.samples.size(),
      rc.edge_sampling.num_points, esvo_samples.size(), obs.timings.time_surface_ms,
      obs.timings.derived_ms, obs.timings.aa_ms, obs.timings.sampling_ms);
  ctx.out << "wrote " << options.out_dir << "/{";
  for (std::size_t i = 0; i < written->size(); ++i)
    ctx.out << (i ? "," : "") << (*written)[i];
  ctx.out << "}\n";
  return Status::Ok();
}

}  // namespace

void RegisterRepresentations(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<RepresentationsOptions>();
  CLI::App* sub = app.add_subcommand(
      "representations",
      "Write one tick's time surfaces, AA map and edge samples as PNGs, to look at them");
  sub->add_option("sequence", options->sequence, "sequence.yaml, DSEC folder or bag")->required();
  sub->add_option("--at", options->at_s, "Seconds from the start of the sequence")
      ->required()
      ->check(DataSeconds());
  sub->add_option("--out", options->out_dir, "Folder for the PNGs")->required();
  sub->add_option("--calib", options->calibration, "Calibration, if the sequence names none");
  sub->add_option("--history", options->history_s,
                  "Seconds of events read before --at (the time surface's memory)")
      ->check(NumberIn(0.0, 60.0));
  AddConfigOptions(*sub, &options->config);
  sub->callback([&ctx, options] {
    ctx.action = [&ctx, options] {
      int exit_code = kExitError;
      const Status status = Run(*options, ctx, &exit_code);
      if (status.ok()) return static_cast<int>(kExitOk);
      ctx.err << "aavio representations: error: " << status.message() << "\n";
      return exit_code;
    };
  });
}

}  // namespace aavio::cli
