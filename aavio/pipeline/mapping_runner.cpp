#include "aavio/pipeline/mapping_runner.hpp"

#include <chrono>

namespace aavio::pipeline {

MappingRunner::Mode MappingRunner::ModeOf(const PipelineConfig& config) {
  if (config.real_time) return Mode::kRealTime;
  return config.concurrent_mapping ? Mode::kConcurrent : Mode::kInline;
}

MappingRunner::MappingRunner(const mapping::RectifiedStereo& stereo, const cv::Mat& valid_mask,
                             const mapping::MappingConfig& config, Mode mode, TimeNs cycle_ns)
    : mapper_(stereo, valid_mask, config), mode_(mode), cycle_ns_(cycle_ns) {}

MappingRunner::~MappingRunner() {
  if (pending_.valid()) pending_.wait();
}

MappingRunner::Cycle MappingRunner::RunCycle(const mapping::PosedObservation& now,
                                             const mapping::TemporalHistory::Partners& partners,
                                             Status* status) {
  Cycle cycle;
  *status = mapper_.Update(now, partners.main_ptr(), &cycle.report, partners.check_ptr());
  if (status->ok() && cycle.report.published) {
    cycle.map = mapper_.local_map();
    cycle.observation = now.obs;
  }
  return cycle;
}

Expected<std::optional<MappingRunner::Cycle>> MappingRunner::Collect(TimeNs t_ns,
                                                                     double* waited_ms) {
  *waited_ms = 0.0;
  if (!pending_.valid()) return std::optional<Cycle>();
  if (mode_ == Mode::kRealTime) {
    if (pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
      return std::optional<Cycle>();
  } else if (t_ns - pending_t_ns_ < cycle_ns_) {
    return std::optional<Cycle>();
  }
  const auto start = std::chrono::steady_clock::now();
  Pending done = pending_.get();
  if (mode_ != Mode::kRealTime) {
    *waited_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  AAVIO_RETURN_IF_ERROR(done.status);
  return std::optional<Cycle>(std::move(done.cycle));
}

Expected<std::optional<MappingRunner::Cycle>> MappingRunner::Start(
    TimeNs t_ns, const mapping::PosedObservation& now, mapping::TemporalHistory::Partners partners,
    bool* skipped) {
  *skipped = false;
  if (mode_ == Mode::kInline) {
    Status status = Status::Ok();
    Cycle cycle = RunCycle(now, partners, &status);
    AAVIO_RETURN_IF_ERROR(status);
    return std::optional<Cycle>(std::move(cycle));
  }
  if (pending_.valid()) {
    *skipped = true;  // the last cycle still runs: this one is dropped
    return std::optional<Cycle>();
  }
  pending_t_ns_ = t_ns;
  // The partners are copies: later observations may be remembered meanwhile.
  pending_ = std::async(std::launch::async, [this, now, partners = std::move(partners)] {
    Pending done;
    done.cycle = RunCycle(now, partners, &done.status);
    return done;
  });
  return std::optional<Cycle>();
}

void MappingRunner::Reset() {
  if (pending_.valid()) pending_.get();  // a cycle of the old map: dropped
  mapper_.Reset();
}

}  // namespace aavio::pipeline
