#include "sequence_opening.hpp"

namespace aavio::cli {

Expected<OpenedSequence> OpenSequence(const std::string& path, const std::string& calibration,
                                      int passes) {
  Expected<io::SequenceDescription> description = io::DescribeSequence(path, calibration);
  if (!description) return description.status();
  if (description->calibration.empty()) {
    return InvalidArgument(path + ": the sequence names no calibration; give one with --calib");
  }
  Expected<io::LoadedCalibration> loaded = io::LoadCalibration(description->calibration);
  if (!loaded) return loaded.status();
  io::SequenceReaderOptions options;
  options.stream.width = loaded->rig.width();
  options.stream.height = loaded->rig.height();
  options.passes = passes;
  Expected<std::unique_ptr<io::SequenceReader>> reader =
      io::SequenceReader::Open(*description, options);
  if (!reader) return reader.status();
  return OpenedSequence{std::move(*description), std::move(*loaded), std::move(*reader)};
}

Expected<recording::RunGroundTruth> LoadRunGroundTruth(const std::string& path) {
  Expected<OpenedSequence> opened = OpenSequence(path, "");
  if (!opened) return opened.status();
  return recording::RunGroundTruth::Of(opened->description, opened->calibration.rig);
}

}  // namespace aavio::cli
