#include "aavio/io/sequence_writer.hpp"

#include <filesystem>

#include "aavio/io/formats/dsec_h5/dsec_h5_writer.hpp"
#include "aavio/io/formats/text/text_streams.hpp"
#include "aavio/io/trajectory_io.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

Expected<SequenceFormat> ParseSequenceFormat(const std::string& name) {
  if (name == "h5") return SequenceFormat::kDsecH5;
  if (name == "bag") return SequenceFormat::kBag;
  if (name == "txt") return SequenceFormat::kText;
  return InvalidArgument("format must be h5, bag or txt, got '" + name + "'");
}

struct SequenceWriter::State {
  fs::path folder;
  SequenceWriterOptions options;
  std::string event_paths[2];
  std::unique_ptr<DsecH5EventWriter> h5[2];
  std::unique_ptr<TextEventWriter> txt[2];
  std::unique_ptr<BagWriter> bag;
  std::vector<imu::ImuSample> imu;  // files formats: written at Close
  bool has_imu = false;
  bool has_poses = false;
  bool closed = false;
};

SequenceWriter::SequenceWriter(std::unique_ptr<State> s) : s_(std::move(s)) {}

SequenceWriter::~SequenceWriter() {
  if (s_ && !s_->closed) {
    SequenceDescription ignored;
    (void)Close(&ignored);
  }
}

Expected<std::unique_ptr<SequenceWriter>> SequenceWriter::Create(
    const std::string& folder, const SequenceWriterOptions& options) {
  auto s = std::make_unique<State>();
  s->folder = folder;
  s->options = options;
  std::error_code ec;
  fs::create_directories(s->folder, ec);
  if (ec) return IoError(folder + ": cannot create the folder (" + ec.message() + ")");
  if (options.format == SequenceFormat::kBag) {
    s->event_paths[0] = s->event_paths[1] = (s->folder / "events.bag").string();
    auto bag = BagWriter::Create(
        s->event_paths[0],
        {.compression = options.compression, .width = options.width, .height = options.height});
    if (!bag) return bag.status();
    s->bag = std::move(*bag);
  } else {
    const bool h5 = options.format == SequenceFormat::kDsecH5;
    for (int side = 0; side < 2; ++side) {
      const fs::path sub = s->folder / "events" / (side == 0 ? "left" : "right");
      fs::create_directories(sub, ec);
      if (ec) return IoError(sub.string() + ": cannot create the folder (" + ec.message() + ")");
      s->event_paths[side] = (sub / (h5 ? "events.h5" : "events.txt")).string();
      if (h5) {
        auto w = DsecH5EventWriter::Create(s->event_paths[side]);
        if (!w) return w.status();
        s->h5[side] = std::move(*w);
      } else {
        auto w = TextEventWriter::Create(s->event_paths[side]);
        if (!w) return w.status();
        s->txt[side] = std::move(*w);
      }
    }
  }
  return std::unique_ptr<SequenceWriter>(new SequenceWriter(std::move(s)));
}

Status SequenceWriter::WriteEvents(bool left, std::span<const events::Event> events) {
  State& s = *s_;
  if (s.bag) return s.bag->WriteEvents(left ? "/davis/left/events" : "/davis/right/events", events);
  const int side = left ? 0 : 1;
  return s.h5[side] ? s.h5[side]->Write(events) : s.txt[side]->Write(events);
}

Status SequenceWriter::WriteImu(std::span<const imu::ImuSample> samples) {
  State& s = *s_;
  s.has_imu = s.has_imu || !samples.empty();
  if (!s.bag) {
    s.imu.insert(s.imu.end(), samples.begin(), samples.end());
    return Status::Ok();
  }
  for (const imu::ImuSample& sample : samples) {
    AAVIO_RETURN_IF_ERROR(s.bag->WriteImu("/davis/left/imu", sample));
  }
  return Status::Ok();
}

Status SequenceWriter::WritePoses(const std::vector<geometry::StampedPose>& poses) {
  State& s = *s_;
  s.has_poses = !poses.empty();
  if (s.bag) {
    for (const geometry::StampedPose& p : poses)
      AAVIO_RETURN_IF_ERROR(s.bag->WritePose("/gt/pose", p));
  }
  return WriteTumTrajectory((s.folder / "groundtruth.txt").string(), poses);
}

Status SequenceWriter::Close(SequenceDescription* d) {
  State& s = *s_;
  if (s.closed) return Status::Ok();
  s.closed = true;
  SourceFormat format = SourceFormat::kBag;
  if (s.bag) {
    AAVIO_RETURN_IF_ERROR(s.bag->Close());
  } else {
    format = s.h5[0] ? SourceFormat::kDsecH5 : SourceFormat::kText;
    for (int side = 0; side < 2; ++side) {
      AAVIO_RETURN_IF_ERROR(s.h5[side] ? s.h5[side]->Close() : s.txt[side]->Close());
    }
  }
  d->left = {format, s.event_paths[0], s.bag ? "/davis/left/events" : "", {}};
  d->right = {format, s.event_paths[1], s.bag ? "/davis/right/events" : "", {}};
  if (s.has_imu) {
    if (s.bag) {
      d->imu = SourceSpec{SourceFormat::kBag, s.event_paths[0], "/davis/left/imu", {}};
    } else {
      const std::string path = (s.folder / "imu.txt").string();
      AAVIO_RETURN_IF_ERROR(WriteImuText(path, s.imu));
      d->imu = SourceSpec{SourceFormat::kText, path, "", ImuTextLayout::kEcd};
    }
  }
  if (s.has_poses) {
    d->gt_trajectory =
        SourceSpec{SourceFormat::kText, (s.folder / "groundtruth.txt").string(), "", {}};
  }
  return Status::Ok();
}

}  // namespace aavio::io
