#pragma once
/// Renders what a camera sees of a scene, pixel by pixel in the camera's own (raw, distorted)
/// pixel grid, as a sensor sees it: one ray per pixel centre through the calibrated model,
/// the albedo of the nearest surface box-filtered over the pixel's footprint (no aliasing), and
/// the depth z of that surface in the camera frame.

#include <vector>

#include "aavio/geometry/camera_model.hpp"
#include "aavio/sim/scene.hpp"

namespace aavio::sim {

struct RenderedImage {
  int width = 0;
  int height = 0;
  std::vector<float> intensity;  ///< linear, in (0, 1]
  std::vector<float> depth_m;    ///< z in the camera frame; 0 where nothing was hit
};

class Renderer {
 public:
  /// Precomputes the ray of every pixel (undistortion happens once, here).
  explicit Renderer(const geometry::CameraModel& camera);

  void Render(const Scene& scene, const geometry::RigidTransform& T_world_cam,
              RenderedImage* out) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  std::vector<Eigen::Vector3d> rays_;  // unit rays in the camera frame (zero if invalid)
  std::vector<float> ray_z_;           // z component of each unit ray (depth = distance · z)
  double pixel_angle_ = 0.0;           // ~1/f: the angle a pixel subtends [rad]
};

}  // namespace aavio::sim
