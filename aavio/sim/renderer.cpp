#include "aavio/sim/renderer.hpp"

#include <algorithm>

namespace aavio::sim {

Renderer::Renderer(const geometry::CameraModel& camera)
    : width_(camera.width()), height_(camera.height()) {
  rays_.resize(static_cast<std::size_t>(width_) * height_, Eigen::Vector3d::Zero());
  ray_z_.resize(rays_.size(), 0.0f);
  for (int v = 0; v < height_; ++v) {
    for (int u = 0; u < width_; ++u) {
      Eigen::Vector3d ray;
      if (!camera.Unproject(Eigen::Vector2d(u, v), &ray)) continue;
      const std::size_t i = static_cast<std::size_t>(v) * width_ + u;
      rays_[i] = ray.normalized();
      ray_z_[i] = static_cast<float>(rays_[i].z());
    }
  }
  const geometry::CameraIntrinsics& in = camera.intrinsics();
  pixel_angle_ = 2.0 / (in.fx + in.fy);
}

void Renderer::Render(const Scene& scene, const geometry::RigidTransform& T_world_cam,
                      RenderedImage* out) const {
  out->width = width_;
  out->height = height_;
  out->intensity.assign(rays_.size(), static_cast<float>(scene.sky_albedo));
  out->depth_m.assign(rays_.size(), 0.0f);
  const Eigen::Vector3d& origin = T_world_cam.t;
  for (std::size_t i = 0; i < rays_.size(); ++i) {
    if (rays_[i].z() == 0.0) continue;
    const Eigen::Vector3d dir = T_world_cam.R * rays_[i];
    Hit hit;
    if (!scene.Intersect(origin, dir, &hit)) continue;
    // The pixel's footprint on the surface, stretched by the grazing angle.
    const double footprint = hit.distance * pixel_angle_ / std::max(hit.cos_incidence, 0.1);
    out->intensity[i] =
        static_cast<float>(scene.quads()[hit.quad].texture.Albedo(hit.u_m, hit.v_m, footprint));
    out->depth_m[i] = static_cast<float>(hit.distance * static_cast<double>(ray_z_[i]));
  }
}

}  // namespace aavio::sim
