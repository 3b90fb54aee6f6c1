#pragma once
/// Renders what a camera sees of a scene, pixel by pixel in the camera's own (raw, distorted)
/// pixel grid, as a sensor sees it: the ray of every pixel centre through the calibrated model,
/// the albedo of the nearest surface box-filtered over the pixel's footprint (no aliasing), and
/// the depth z of that surface in the camera frame.
///
/// Rasterisation rather than per-pixel ray casting: the rays are undistorted once, binned on a
/// grid of their normalised image coordinates (x/z, y/z); every quad is clipped to the front of
/// the camera, projected, and tested only against the pixels of the grid cells it covers
/// (z-buffer); the texture is evaluated once per pixel afterwards. Exactly the result of ray
/// casting (tested against Scene::Intersect), several times faster.

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
  /// Precomputes the ray of every pixel (undistortion happens once, here) and the grid.
  explicit Renderer(const geometry::CameraModel& camera);

  /// The scene as seen at `t_ns` (moving quads displaced and light sources flickering from
  /// the scene's time origin; a static, steady scene looks the same at every time).
  void Render(const Scene& scene, const geometry::RigidTransform& T_world_cam, TimeNs t_ns,
              RenderedImage* out) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  std::vector<float> nx_, ny_;  // normalised coordinates x/z, y/z of each pixel's ray (NaN: none)
  double pixel_angle_ = 0.0;    // ~1/f: the angle a pixel subtends [rad]
  // Grid over the normalised coordinates: cell (i, j) holds pixels cell_start_[c] .. [c + 1).
  double grid_x0_ = 0, grid_y0_ = 0, grid_cell_ = 1;
  int grid_w_ = 0, grid_h_ = 0;
  std::vector<std::uint32_t> cell_start_, cell_pixels_;
  // Scratch buffers of a render (mutable: Render is logically const and not shared between
  // threads; each camera has its own Renderer).
  mutable std::vector<float> zbuf_;
  mutable std::vector<std::int32_t> quad_of_;
  mutable std::vector<float> tex_u_, tex_v_;
  mutable std::vector<Eigen::Vector3d> normals_;  // per quad, camera frame, unit
};

}  // namespace aavio::sim
