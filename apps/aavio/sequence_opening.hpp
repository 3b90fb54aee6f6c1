#pragma once
/// What the commands that process a sequence share: describe it, load its calibration (or the
/// one given with --calib), and open a packet reader that checks events against the sensor size.

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "aavio/common/status.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/recording/run_evaluation.hpp"

namespace aavio::cli {

struct OpenedSequence {
  io::SequenceDescription description;
  io::LoadedCalibration calibration;
  std::unique_ptr<io::SequenceReader> reader;
};

/// `passes`: read the sequence that many times back to back (io::SequenceReaderOptions).
Expected<OpenedSequence> OpenSequence(const std::string& path, const std::string& calibration,
                                      int passes = 1);

/// What a folder of `aavio run` ran on: its summary.json, and the sequence and calibration that
/// summary names, each replaced by `sequence` / `calibration` when not empty (the sequence moved,
/// or a run from before runs recorded their calibration).
struct RunInputs {
  nlohmann::json summary;
  std::string sequence, calibration;
};
Expected<RunInputs> ReadRunInputs(const std::string& run_dir, const std::string& sequence,
                                  const std::string& calibration);

/// The ground truth the sequence a run read names, for evaluating the run.
Expected<recording::RunGroundTruth> LoadRunGroundTruth(const RunInputs& run);

}  // namespace aavio::cli
