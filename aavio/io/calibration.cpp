#include "aavio/io/calibration.hpp"

#include <filesystem>

#include "aavio/io/file_checks.hpp"
#include "aavio/io/yaml_reading.hpp"

namespace aavio::io {

namespace fs = std::filesystem;

namespace {

/// Something is there under this name, whatever it is (the reader then says if it is no file).
bool Present(const fs::path& p) {
  std::error_code ec;
  const fs::file_type type = fs::symlink_status(p, ec).type();
  return type != fs::file_type::not_found && type != fs::file_type::none;
}

/// DSEC's cam_to_cam.yaml has top-level `intrinsics` and `extrinsics`; ESVO files `camera_matrix`.
bool LooksLikeDsec(const std::string& file) {
  Expected<YAML::Node> root = yaml::LoadFile(file);
  return root.ok() && (*root)["intrinsics"] && (*root)["extrinsics"];
}

}  // namespace

Expected<LoadedCalibration> LoadCalibration(const std::string& path) {
  std::error_code ec;
  const fs::path p(path);
  if (!Present(p)) return NotFound(path + ": no such file or folder");
  if (fs::is_directory(p, ec)) {
    if (Present(p / "left.yaml") && Present(p / "right.yaml")) {
      return LoadEsvoCalibration((p / "left.yaml").string(), (p / "right.yaml").string());
    }
    for (const fs::path& candidate :
         {p / "cam_to_cam.yaml", p / "calibration" / "cam_to_cam.yaml"}) {
      if (Present(candidate)) return LoadDsecCalibration(candidate.string());
    }
    return NotFound(path +
                    ": no calibration here; expected left.yaml + right.yaml (ESVO), "
                    "cam_to_cam.yaml or calibration/cam_to_cam.yaml (DSEC)");
  }
  AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "calibration file"));
  if (LooksLikeDsec(path)) return LoadDsecCalibration(path);
  // ESVO: either file of the pair; the other one sits beside it.
  const std::string name = p.filename().string();
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (name.find("left") != std::string::npos || name.find("right") != std::string::npos) {
    const bool is_left = name.find("left") != std::string::npos;
    std::string other = name;
    other.replace(other.find(is_left ? "left" : "right"), is_left ? 4 : 5,
                  is_left ? "right" : "left");
    const fs::path other_path = dir / other;
    if (!Present(other_path)) {
      return NotFound(path + ": an ESVO calibration needs both cameras, but " +
                      other_path.string() + " does not exist");
    }
    return is_left ? LoadEsvoCalibration(path, other_path.string())
                   : LoadEsvoCalibration(other_path.string(), path);
  }
  Expected<YAML::Node> root = yaml::LoadFile(path);
  if (!root) return root.status();
  return InvalidArgument(path +
                         ": not a calibration aavio knows; give a folder with left.yaml + "
                         "right.yaml (ESVO), one of those files, or a DSEC cam_to_cam.yaml");
}

}  // namespace aavio::io
