// Calibration YAML: an ESVO left.yaml + right.yaml pair (the input's two parts, see SplitTwo)
// and a DSEC cam_to_cam.yaml (the whole input).
#include "aavio/io/calibration.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace aavio;
  const auto [left, right] = fuzz::SplitTwo(data, size);
  const std::string left_path = fuzz::WriteText("left.yaml", left);
  const std::string right_path = fuzz::WriteText("right.yaml", right);
  (void)io::LoadEsvoCalibration(left_path, right_path);
  const std::string dsec_path = fuzz::WriteInput("cam_to_cam.yaml", data, size);
  (void)io::LoadDsecCalibration(dsec_path);
  return 0;
}
