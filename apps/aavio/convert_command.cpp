// `aavio convert SEQUENCE --to bag|h5|txt --out DIR`: rewrites a sequence's events, IMU and
// ground-truth poses in another format, streaming (memory stays bounded), and writes a
// sequence.yaml for the result. E.g. a DSEC folder to a bag for ROS tools.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <ostream>

#include "aavio/common/format.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/formats/rosbag/bag_streams.hpp"
#include "aavio/io/output_folder.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/sequence_writer.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "cli.hpp"
#include "option_checks.hpp"

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
  bool overwrite = false;
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

  // The input's own folder would lose its files to --overwrite.
  const fs::path input_folder = fs::is_directory(options.input)
                                    ? fs::path(options.input)
                                    : fs::path(options.input).parent_path();
  std::error_code ec;
  if (fs::exists(options.out, ec) &&
      fs::equivalent(input_folder.empty() ? "." : input_folder, options.out, ec)) {
    return InvalidArgument(
        options.out + ": is the folder of the sequence being converted; give --out another folder");
  }
  AAVIO_RETURN_IF_ERROR(io::PrepareOutputFolder(
      options.out, {.outputs = io::kSequenceOutputs, .overwrite = options.overwrite}));
  Expected<io::SequenceFormat> format = io::ParseSequenceFormat(options.to);
  if (!format) return format.status();
  const io::BagCompression compression = options.compression == "none"  ? io::BagCompression::kNone
                                         : options.compression == "bz2" ? io::BagCompression::kBz2
                                                                        : io::BagCompression::kLz4;
  Expected<std::unique_ptr<io::SequenceWriter>> writer = io::SequenceWriter::Create(
      options.out,
      {.format = *format, .width = width, .height = height, .compression = compression});
  if (!writer) return writer.status();
  io::SequenceWriter& sink = **writer;

  io::SensorPacket packet;
  std::int64_t left = 0, right = 0, imu = 0;
  while (true) {
    Expected<bool> more = (*reader)->Next(&packet);
    if (!more) return more.status();
    if (!*more) break;
    AAVIO_RETURN_IF_ERROR(sink.WriteEvents(true, packet.left));
    AAVIO_RETURN_IF_ERROR(sink.WriteEvents(false, packet.right));
    AAVIO_RETURN_IF_ERROR(sink.WriteImu(packet.imu));
    left += static_cast<std::int64_t>(packet.left.size());
    right += static_cast<std::int64_t>(packet.right.size());
    imu += static_cast<std::int64_t>(packet.imu.size());
  }
  if (in->gt_trajectory) {
    Expected<std::vector<geometry::StampedPose>> poses =
        io::ReadGroundTruthPoses(*in->gt_trajectory);
    if (!poses) return poses.status();
    AAVIO_RETURN_IF_ERROR(sink.WritePoses(*poses));
  }
  io::SequenceDescription out;
  out.name = in->name;
  out.calibration = in->calibration.empty() ? "" : fs::absolute(in->calibration).string();
  out.gt_depth = in->gt_depth.empty() ? "" : fs::absolute(in->gt_depth).string();
  out.gt_calibration = in->gt_calibration.empty() ? "" : fs::absolute(in->gt_calibration).string();
  AAVIO_RETURN_IF_ERROR(sink.Close(&out));
  const std::string yaml = (fs::path(options.out) / "sequence.yaml").string();
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
  sub->add_flag("--overwrite", options->overwrite,
                "Replace a sequence already in --out (else that is an error)");
  sub->add_option("--calib", options->calibration,
                  "Calibration (for a bag without a sequence.yaml)");
  sub->add_option("--compression", options->compression, "Bag chunk compression")
      ->check(CLI::IsMember({"none", "lz4", "bz2"}));
  sub->add_option("--max-reorder-ms", options->max_reorder_ms,
                  "Reorder events up to this far out of time order (more is an error)")
      ->check(NumberIn(0.0, 60000.0));
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
