#include "sequence_opening.hpp"

#include <filesystem>

#include "aavio/io/file_checks.hpp"
#include "aavio/recording/run_recorder.hpp"

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

Expected<RunInputs> ReadRunInputs(const std::string& run_dir, const std::string& sequence,
                                  const std::string& calibration) {
  const std::filesystem::path summary_path =
      std::filesystem::path(run_dir) / recording::run_files::kSummary;
  std::error_code ec;
  if (!std::filesystem::exists(summary_path, ec)) {
    return NotFound(summary_path.string() +
                    ": not found; --run takes a folder written by `aavio run`");
  }
  Expected<std::string> text =
      io::ReadBoundedFile(summary_path.string(), io::kMaxSettingsFileBytes, "run summary");
  if (!text) return text.status();
  RunInputs run;
  try {
    run.summary = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::exception& e) {
    return ParseError(summary_path.string() + ": not valid JSON (" + e.what() + ")");
  }
  if (!run.summary.is_object()) return ParseError(summary_path.string() + ": not a JSON object");
  auto entry = [&](const char* key) {
    const auto it = run.summary.find(key);
    return it != run.summary.end() && it->is_string() ? it->get<std::string>() : std::string();
  };
  run.sequence = sequence.empty() ? entry("sequence") : sequence;
  run.calibration = calibration;
  // The recorded one, unless it has gone since (then the sequence's own, if it names one).
  if (run.calibration.empty() && std::filesystem::exists(entry("calibration"), ec))
    run.calibration = entry("calibration");
  if (run.sequence.empty()) {
    return ParseError(summary_path.string() +
                      ": names no sequence; name the one the run read with --sequence");
  }
  return run;
}

Expected<recording::RunGroundTruth> LoadRunGroundTruth(const RunInputs& run) {
  Expected<OpenedSequence> opened = OpenSequence(run.sequence, run.calibration);
  if (!opened) return opened.status();
  return recording::RunGroundTruth::Of(opened->description, opened->calibration.rig);
}

}  // namespace aavio::cli
