// `aavio convert SEQUENCE --to bag|h5|txt --out DIR`: rewrites a sequence's events, IMU and
// ground-truth poses in another format, streaming (memory stays bounded), and writes a
// sequence.yaml for the result. E.g. a DSEC folder to a bag for ROS tools.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/io/bag_streams.hpp"
#include "aavio/io/bag_writer.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/dsec_h5_writer.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/text_streams.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "cli.hpp"

namespace aavio::cli {

namespace {

namespace fs = std::filesystem;

struct ConvertOptions {
  std::string input;
  std::string calibration;
  std::string to = "bag";
  std::string out;
  std::string compression = "lz4";
  double max_reorder_ms = 10.0;
};

/// The three kinds of output behind one interface: events per side, IMU samples, poses.
class SequenceSink {
 public:
  virtual ~SequenceSink() = default;
  virtual Status Events(bool left, std::span<const events::Event> events) = 0;
  virtual Status Imu(std::span<const imu::ImuSample> samples) = 0;
  virtual Status Poses(const std::vector<geometry::StampedPose>& poses) = 0;
  virtual Status Close(io::SequenceDescription* d) = 0;
};

class BagSink final : public SequenceSink {
 public:
  static Expected<std::unique_ptr<BagSink>> Create(const fs::path& dir, io::BagCompression c,
                                                   int width, int height) {
    auto writer = io::BagWriter::Create((dir / "events.bag").string(),
                                        {.compression = c, .width = width, .height = height});
    if (!writer) return writer.status();
    auto sink = std::make_unique<BagSink>();
    sink->writer_ = std::move(*writer);
    sink->path_ = (dir / "events.bag").string();
    return sink;
  }
  Status Events(bool left, std::span<const events::Event> events) override {
    return writer_->WriteEvents(left ? "/davis/left/events" : "/davis/right/events", events);
  }
  Status Imu(std::span<const imu::ImuSample> samples) override {
    has_imu_ = has_imu_ || !samples.empty();
    for (const imu::ImuSample& s : samples)
      AAVIO_RETURN_IF_ERROR(writer_->WriteImu("/davis/left/imu", s));
    return Status::Ok();
  }
  Status Poses(const std::vector<geometry::StampedPose>& poses) override {
    has_poses_ = !poses.empty();
    for (const geometry::StampedPose& p : poses)
      AAVIO_RETURN_IF_ERROR(writer_->WritePose("/gt/pose", p));
    return Status::Ok();
  }
  Status Close(io::SequenceDescription* d) override {
    AAVIO_RETURN_IF_ERROR(writer_->Close());
    d->left = {io::SourceFormat::kBag, path_, "/davis/left/events", {}};
    d->right = {io::SourceFormat::kBag, path_, "/davis/right/events", {}};
    if (has_imu_) d->imu = io::SourceSpec{io::SourceFormat::kBag, path_, "/davis/left/imu", {}};
    if (has_poses_)
      d->gt_trajectory = io::SourceSpec{io::SourceFormat::kBag, path_, "/gt/pose", {}};
    return Status::Ok();
  }

 private:
  std::unique_ptr<io::BagWriter> writer_;
  std::string path_;
  bool has_imu_ = false, has_poses_ = false;
};

/// h5 (DSEC layout) or text events; IMU as imu.txt and poses as groundtruth.txt beside them.
class FileSink final : public SequenceSink {
 public:
  static Expected<std::unique_ptr<FileSink>> Create(const fs::path& dir, bool h5) {
    auto sink = std::make_unique<FileSink>();
    sink->dir_ = dir;
    sink->h5_ = h5;
    for (int side = 0; side < 2; ++side) {
      const fs::path sub = dir / "events" / (side == 0 ? "left" : "right");
      fs::create_directories(sub);
      sink->paths_[side] = (sub / (h5 ? "events.h5" : "events.txt")).string();
      if (h5) {
        auto w = io::DsecH5EventWriter::Create(sink->paths_[side]);
        if (!w) return w.status();
        sink->h5_writers_[side] = std::move(*w);
      } else {
        auto w = io::TextEventWriter::Create(sink->paths_[side]);
        if (!w) return w.status();
        sink->text_writers_[side] = std::move(*w);
      }
    }
    return sink;
  }
  Status Events(bool left, std::span<const events::Event> events) override {
    const int side = left ? 0 : 1;
    return h5_ ? h5_writers_[side]->Write(events) : text_writers_[side]->Write(events);
  }
  Status Imu(std::span<const imu::ImuSample> samples) override {
    imu_.insert(imu_.end(), samples.begin(), samples.end());  // small: ~1 kHz × 48 bytes
    return Status::Ok();
  }
  Status Poses(const std::vector<geometry::StampedPose>& poses) override {
    poses_ = poses;
    return Status::Ok();
  }
  Status Close(io::SequenceDescription* d) override {
    const io::SourceFormat format = h5_ ? io::SourceFormat::kDsecH5 : io::SourceFormat::kText;
    for (int side = 0; side < 2; ++side) {
      AAVIO_RETURN_IF_ERROR(h5_ ? h5_writers_[side]->Close() : text_writers_[side]->Close());
    }
    d->left = {format, paths_[0], "", {}};
    d->right = {format, paths_[1], "", {}};
    if (!imu_.empty()) {
      const std::string path = (dir_ / "imu.txt").string();
      AAVIO_RETURN_IF_ERROR(io::WriteImuText(path, imu_));
      d->imu = io::SourceSpec{io::SourceFormat::kText, path, "", io::ImuTextLayout::kEcd};
    }
    if (!poses_.empty()) {
      const std::string path = (dir_ / "groundtruth.txt").string();
      AAVIO_RETURN_IF_ERROR(io::WriteTumTrajectory(path, poses_));
      d->gt_trajectory = io::SourceSpec{io::SourceFormat::kText, path, "", {}};
    }
    return Status::Ok();
  }

 private:
  fs::path dir_;
  bool h5_ = true;
  std::string paths_[2];
  std::unique_ptr<io::DsecH5EventWriter> h5_writers_[2];
  std::unique_ptr<io::TextEventWriter> text_writers_[2];
  std::vector<imu::ImuSample> imu_;
  std::vector<geometry::StampedPose> poses_;
};

Status Convert(const ConvertOptions& options, Context& ctx) {
  Expected<io::SequenceDescription> in = io::DescribeSequence(options.input, options.calibration);
  if (!in) return in.status();
  io::SequenceReaderOptions reader_options;
  reader_options.packet_ns = 10 * kNsPerMs;
  reader_options.stream.max_reorder_ns = static_cast<TimeNs>(options.max_reorder_ms * 1e6);
  int width = 0, height = 0;
  if (!in->calibration.empty()) {
    Expected<io::LoadedCalibration> calib = io::LoadCalibration(in->calibration);
    if (!calib) return calib.status();
    width = reader_options.stream.width = calib->rig.width();
    height = reader_options.stream.height = calib->rig.height();
  }
  Expected<std::unique_ptr<io::SequenceReader>> reader =
      io::SequenceReader::Open(*in, reader_options);
  if (!reader) return reader.status();
  if (width == 0) {
    width = (*reader)->left().info().width;
    height = (*reader)->left().info().height;
  }

  const fs::path out_dir(options.out);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) return IoError(options.out + ": cannot create the folder (" + ec.message() + ")");
  std::unique_ptr<SequenceSink> sink;
  if (options.to == "bag") {
    const io::BagCompression c = options.compression == "none"  ? io::BagCompression::kNone
                                 : options.compression == "bz2" ? io::BagCompression::kBz2
                                                                : io::BagCompression::kLz4;
    auto s = BagSink::Create(out_dir, c, width, height);
    if (!s) return s.status();
    sink = std::move(*s);
  } else {
    auto s = FileSink::Create(out_dir, options.to == "h5");
    if (!s) return s.status();
    sink = std::move(*s);
  }

  io::SensorPacket packet;
  std::int64_t left = 0, right = 0, imu = 0;
  while (true) {
    Expected<bool> more = (*reader)->Next(&packet);
    if (!more) return more.status();
    if (!*more) break;
    AAVIO_RETURN_IF_ERROR(sink->Events(true, packet.left));
    AAVIO_RETURN_IF_ERROR(sink->Events(false, packet.right));
    AAVIO_RETURN_IF_ERROR(sink->Imu(packet.imu));
    left += static_cast<std::int64_t>(packet.left.size());
    right += static_cast<std::int64_t>(packet.right.size());
    imu += static_cast<std::int64_t>(packet.imu.size());
  }
  if (in->gt_trajectory) {
    Expected<std::vector<geometry::StampedPose>> poses =
        in->gt_trajectory->format == io::SourceFormat::kBag
            ? io::ReadBagPoses(in->gt_trajectory->path, in->gt_trajectory->topic)
            : io::ReadTumTrajectory(in->gt_trajectory->path);
    if (!poses) return poses.status();
    AAVIO_RETURN_IF_ERROR(sink->Poses(*poses));
  }
  io::SequenceDescription out;
  out.name = in->name;
  out.calibration = in->calibration.empty() ? "" : fs::absolute(in->calibration).string();
  out.gt_depth = in->gt_depth.empty() ? "" : fs::absolute(in->gt_depth).string();
  AAVIO_RETURN_IF_ERROR(sink->Close(&out));
  const std::string yaml = (out_dir / "sequence.yaml").string();
  AAVIO_RETURN_IF_ERROR(io::WriteSequenceYaml(yaml, out));
  ctx.out << StrFormat("converted %lld left + %lld right events and %lld IMU samples to %s\n",
                       static_cast<long long>(left), static_cast<long long>(right),
                       static_cast<long long>(imu), options.to.c_str())
          << "wrote " << yaml << "\n";
  return Status::Ok();
}

}  // namespace

void RegisterConvert(CLI::App& app, Context& ctx) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* sub = app.add_subcommand(
      "convert",
      "Rewrite a sequence (sequence.yaml, DSEC folder or bag) as a ROS bag, DSEC-layout "
      "h5 or text, with a sequence.yaml for the result");
  sub->add_option("sequence", options->input, "Sequence to convert")->required();
  sub->add_option("--to", options->to, "Output format")->check(CLI::IsMember({"bag", "h5", "txt"}));
  sub->add_option("--out", options->out, "Output folder")->required();
  sub->add_option("--calib", options->calibration,
                  "Calibration (for a bag without a sequence.yaml)");
  sub->add_option("--compression", options->compression, "Bag chunk compression")
      ->check(CLI::IsMember({"none", "lz4", "bz2"}));
  sub->add_option("--max-reorder-ms", options->max_reorder_ms,
                  "Reorder events up to this far out of time order (more is an error)");
  sub->callback([&ctx, options] {
    ctx.action = [&ctx, options] {
      Status status = Convert(*options, ctx);
      if (status.ok()) return static_cast<int>(kExitOk);
      ctx.err << "aavio convert: error: " << status.message() << "\n";
      return static_cast<int>(kExitError);
    };
  });
}

}  // namespace aavio::cli
