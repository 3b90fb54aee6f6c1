#pragma once
/// What the commands that process a sequence share: describe it, load its calibration (or the
/// one given with --calib), and open a packet reader that checks events against the sensor size.

#include <memory>
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

/// The ground truth the sequence at `path` names, for evaluating a run of it.
Expected<recording::RunGroundTruth> LoadRunGroundTruth(const std::string& path);

}  // namespace aavio::cli
