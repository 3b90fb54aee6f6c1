#include "aavio/events/representation_builder.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <opencv2/core.hpp>

#include "aavio/events/edge_sampler.hpp"
#include "aavio/events/ts_images.hpp"

namespace aavio::events {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// SplitMix64: a tick's own seed from the run's seed and the tick's time since the epoch.
std::uint64_t TickSeed(std::uint64_t seed, TimeNs t_ns) {
  std::uint64_t z = seed ^ (static_cast<std::uint64_t>(t_ns) * 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace

RepresentationBuilder::RepresentationBuilder(const geometry::StereoRectification& rectification,
                                             int width, int height,
                                             const RepresentationConfig& config, TimeNs epoch_ns)
    : config_(config),
      rectification_(rectification),
      left_{TimeSurface(width, height, epoch_ns),
            ImageRectifier(rectification.left),
            {},
            std::numeric_limits<TimeNs>::min()},
      right_{TimeSurface(width, height, epoch_ns),
             ImageRectifier(rectification.right),
             {},
             std::numeric_limits<TimeNs>::min()},
      accumulator_(width, height, config.adaptive_accumulation),
      last_tick_ns_(std::numeric_limits<TimeNs>::min()),
      epoch_ns_(epoch_ns) {}

Status RepresentationBuilder::AddEvents(Camera camera, std::span<const Event> events) {
  CameraState& state = camera == Camera::kLeft ? left_ : right_;
  for (const Event& e : events) {
    if (e.t_ns < state.newest_added_ns) {
      return InvalidArgument(std::string(camera == Camera::kLeft ? "left" : "right") +
                             " events are not in time order at " + FormatSecondsNs(e.t_ns) +
                             " s (after " + FormatSecondsNs(state.newest_added_ns) + " s)");
    }
    if (e.t_ns <= last_tick_ns_) {
      return InvalidArgument("an event at " + FormatSecondsNs(e.t_ns) +
                             " s arrived after the tick at " + FormatSecondsNs(last_tick_ns_) +
                             " s was built");
    }
    state.newest_added_ns = e.t_ns;
  }
  // Beyond the cap the oldest go: of those waiting first, then of this call's.
  const std::size_t cap = config_.max_buffered_events;
  std::size_t from = 0;
  if (events.size() >= cap) {
    dropped_events_ += static_cast<std::int64_t>(state.pending.size() + events.size() - cap);
    state.pending.clear();
    from = events.size() - cap;
  } else if (state.pending.size() + events.size() > cap) {
    const std::size_t excess = state.pending.size() + events.size() - cap;
    dropped_events_ += static_cast<std::int64_t>(excess);
    state.pending.erase(state.pending.begin(),
                        state.pending.begin() + static_cast<std::ptrdiff_t>(excess));
  }
  state.pending.insert(state.pending.end(), events.begin() + static_cast<std::ptrdiff_t>(from),
                       events.end());
  return Status::Ok();
}

Status RepresentationBuilder::Consume(CameraState& camera, TimeNs t_ns, bool keep_window,
                                      std::int64_t* consumed) {
  const auto end = std::upper_bound(camera.pending.begin(), camera.pending.end(), t_ns,
                                    [](TimeNs t, const Event& e) { return t < e.t_ns; });
  std::span<const Event> batch(camera.pending.begin(), end);
  *consumed = static_cast<std::int64_t>(batch.size());
  AAVIO_RETURN_IF_ERROR(camera.ts.Insert(batch));
  if (keep_window) window_.insert(window_.end(), batch.begin(), batch.end());
  camera.pending.erase(camera.pending.begin(), end);
  return Status::Ok();
}

Status RepresentationBuilder::Build(TimeNs t_ns, Observation* out, BuildOptions options) {
  if (t_ns <= last_tick_ns_) {
    return InvalidArgument("ticks must increase: " + FormatSecondsNs(t_ns) + " s after " +
                           FormatSecondsNs(last_tick_ns_) + " s");
  }
  last_tick_ns_ = t_ns;
  out->t_ns = t_ns;
  AAVIO_RETURN_IF_ERROR(Consume(left_, t_ns, true, &out->new_events_left));
  AAVIO_RETURN_IF_ERROR(Consume(right_, t_ns, false, &out->new_events_right));
  RenderTimeSurfaces(t_ns, options, out);
  DeriveGradients(out);
  const std::span<const Event> recent = RecentLeftEvents(t_ns);
  if (!options.edges) return Status::Ok();
  BuildAaMap(recent, t_ns, out);
  SampleEdges(recent, t_ns, out);
  return Status::Ok();
}

void RepresentationBuilder::RenderTimeSurfaces(TimeNs t_ns, const BuildOptions& options,
                                               Observation* out) {
  // Raw → rectified (bilinear) → median.
  const auto start = Clock::now();
  const double decay_ms = options.decay_ms > 0.0 ? options.decay_ms : config_.time_surface.decay_ms;
  for (CameraState* camera : {&left_, &right_}) {
    if (camera == &right_ && !options.right_ts) {
      out->ts_right.release();
      continue;
    }
    cv::Mat& ts = camera == &left_ ? out->ts_left : out->ts_right;
    if (padded_.empty()) padded_ = camera->rectifier.MakePadded();
    cv::Mat interior = ImageRectifier::PaddedInterior(padded_);
    camera->ts.Render(t_ns, decay_ms, &interior);
    camera->rectifier.RectifyPadded(padded_, &ts);
    MedianFilterTs(ts, &ts);
  }
  out->timings.time_surface_ms = MsSince(start);
}

void RepresentationBuilder::DeriveGradients(Observation* out) const {
  const auto start = Clock::now();
  NegativeTs(out->ts_left, &out->negative_ts_left);
  SobelGradients(out->negative_ts_left, &out->grad_u, &out->grad_v);
  out->timings.derived_ms = MsSince(start);
}

std::span<const Event> RepresentationBuilder::RecentLeftEvents(TimeNs t_ns) {
  // Only what AA and ESVO's selection look at.
  const double keep_ms = std::max(config_.adaptive_accumulation.window_ms, kNewestEventsWindowMs);
  const TimeNs keep_from = t_ns - SecondsToNs(keep_ms * 1e-3);
  while (window_begin_ < window_.size() && window_[window_begin_].t_ns <= keep_from)
    ++window_begin_;
  // The newest max_buffered_events at most (they are all in the time surface already).
  window_begin_ = std::max(window_begin_,
                           window_.size() - std::min(window_.size(), config_.max_buffered_events));
  if (window_begin_ > window_.size() / 2) {
    window_.erase(window_.begin(), window_.begin() + static_cast<std::ptrdiff_t>(window_begin_));
    window_begin_ = 0;
  }
  return {window_.data() + window_begin_, window_.size() - window_begin_};
}

void RepresentationBuilder::BuildAaMap(std::span<const Event> recent, TimeNs t_ns,
                                       Observation* out) {
  const auto start = Clock::now();
  out->timings.edges = true;
  accumulator_.Build(recent, t_ns, &aa_);
  aa_.counts.copyTo(out->aa_counts_raw);
  if (const int gain = config_.adaptive_accumulation.map_count_gain; gain > 0) {
    aa_.counts.convertTo(scratch_binary_, CV_8U, gain);  // saturates at 255
  } else {
    cv::compare(aa_.counts, 0, scratch_binary_, cv::CMP_GT);
  }
  left_.rectifier.Rectify(scratch_binary_, &out->aa_map);
  out->aa_window_events = aa_.window_events;
  out->aa_used_events = aa_.used_events;
  out->aa_blocks.resize(aa_.blocks.size());
  for (std::size_t b = 0; b < aa_.blocks.size(); ++b) {
    const AaBlock& block = aa_.blocks[b];
    out->aa_blocks[b] = {{}, block.events, block.closed, block.span_ns, block.contrast};
  }
  out->timings.aa_ms = MsSince(start);
}

void RepresentationBuilder::SampleEdges(std::span<const Event> recent, TimeNs t_ns,
                                        Observation* out) const {
  const auto start = Clock::now();
  if (config_.edge_sampling.mode == SamplingMode::kAdaptiveAccumulation) {
    out->samples = SampleAaMap(aa_, rectification_.left, config_.edge_sampling,
                               TickSeed(config_.seed, t_ns - epoch_ns_));
  } else {
    out->samples = SelectNewestEvents(recent, t_ns, rectification_.left, config_.edge_sampling);
  }
  out->timings.sampling_ms = MsSince(start);
}

}  // namespace aavio::events
