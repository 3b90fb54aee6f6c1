#include "aavio/sim/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aavio::sim {

namespace {

constexpr double kNear = 0.01;  // [m] quads are clipped to z >= kNear in the camera frame

/// Sutherland–Hodgman clipping of a polygon to the half-space z >= kNear.
int ClipNear(const Eigen::Vector3d* in, int n, Eigen::Vector3d* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = in[i];
    const Eigen::Vector3d& b = in[(i + 1) % n];
    const bool a_in = a.z() >= kNear, b_in = b.z() >= kNear;
    if (a_in) out[m++] = a;
    if (a_in != b_in) out[m++] = a + (b - a) * ((kNear - a.z()) / (b.z() - a.z()));
  }
  return m;
}

}  // namespace

Renderer::Renderer(const geometry::CameraModel& camera)
    : width_(camera.width()), height_(camera.height()) {
  const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  nx_.assign(n, std::numeric_limits<float>::quiet_NaN());
  ny_.assign(n, std::numeric_limits<float>::quiet_NaN());
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (int v = 0; v < height_; ++v) {
    for (int u = 0; u < width_; ++u) {
      Eigen::Vector3d ray;
      if (!camera.Unproject(Eigen::Vector2d(u, v), &ray)) continue;
      const std::size_t i = static_cast<std::size_t>(v) * static_cast<std::size_t>(width_) +
                            static_cast<std::size_t>(u);
      nx_[i] = static_cast<float>(ray.x());
      ny_[i] = static_cast<float>(ray.y());
      x0 = std::min(x0, ray.x());
      x1 = std::max(x1, ray.x());
      y0 = std::min(y0, ray.y());
      y1 = std::max(y1, ray.y());
    }
  }
  const geometry::CameraIntrinsics& in = camera.intrinsics();
  pixel_angle_ = 2.0 / (in.fx + in.fy);
  // Cells of ~4 × 4 pixels.
  grid_cell_ = 4.0 * pixel_angle_;
  grid_x0_ = x0 - grid_cell_;
  grid_y0_ = y0 - grid_cell_;
  grid_w_ = static_cast<int>((x1 - grid_x0_) / grid_cell_) + 2;
  grid_h_ = static_cast<int>((y1 - grid_y0_) / grid_cell_) + 2;
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(grid_w_) * grid_h_ + 1, 0);
  auto cell_of = [&](std::size_t i) {
    const int cx = static_cast<int>((static_cast<double>(nx_[i]) - grid_x0_) / grid_cell_);
    const int cy = static_cast<int>((static_cast<double>(ny_[i]) - grid_y0_) / grid_cell_);
    return static_cast<std::size_t>(cy) * static_cast<std::size_t>(grid_w_) +
           static_cast<std::size_t>(cx);
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isnan(nx_[i])) ++counts[cell_of(i) + 1];
  }
  for (std::size_t c = 1; c < counts.size(); ++c)
    counts[c] += counts[c - 1];
  cell_start_ = counts;
  cell_pixels_.resize(counts.back());
  std::vector<std::uint32_t> fill(counts.begin(), counts.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isnan(nx_[i])) cell_pixels_[fill[cell_of(i)]++] = static_cast<std::uint32_t>(i);
  }
}

void Renderer::Render(const Scene& scene, const geometry::RigidTransform& T_world_cam,
                      TimeNs t_ns, RenderedImage* out) const {
  const double t_s = NsToSeconds(t_ns - scene.time_origin_ns);
  const std::size_t n = nx_.size();
  out->width = width_;
  out->height = height_;
  out->intensity.assign(n, static_cast<float>(scene.sky_albedo));
  out->depth_m.assign(n, 0.0f);
  zbuf_.assign(n, std::numeric_limits<float>::infinity());
  quad_of_.assign(n, -1);
  tex_u_.resize(n);
  tex_v_.resize(n);

  const geometry::RigidTransform T_cam_world = T_world_cam.Inverse();
  const std::vector<Quad>& quads = scene.quads();
  for (std::size_t q = 0; q < quads.size(); ++q) {
    const Quad& quad = quads[q];
    const Eigen::Vector3d o = T_cam_world * quad.OriginAt(t_s);
    const Eigen::Vector3d u = T_cam_world.R * quad.edge_u;
    const Eigen::Vector3d v = T_cam_world.R * quad.edge_v;
    const Eigen::Vector3d corners[4] = {o, o + u, o + u + v, o + v};
    Eigen::Vector3d clipped[8];
    const int m = ClipNear(corners, 4, clipped);
    if (m < 3) continue;
    double bx0 = 1e300, bx1 = -1e300, by0 = 1e300, by1 = -1e300;
    for (int k = 0; k < m; ++k) {
      const double x = clipped[k].x() / clipped[k].z(), y = clipped[k].y() / clipped[k].z();
      bx0 = std::min(bx0, x);
      bx1 = std::max(bx1, x);
      by0 = std::min(by0, y);
      by1 = std::max(by1, y);
    }
    const int cx0 = std::max(0, static_cast<int>(std::floor((bx0 - grid_x0_) / grid_cell_)));
    const int cx1 =
        std::min(grid_w_ - 1, static_cast<int>(std::floor((bx1 - grid_x0_) / grid_cell_)));
    const int cy0 = std::max(0, static_cast<int>(std::floor((by0 - grid_y0_) / grid_cell_)));
    const int cy1 =
        std::min(grid_h_ - 1, static_cast<int>(std::floor((by1 - grid_y0_) / grid_cell_)));
    if (cx0 > cx1 || cy0 > cy1) continue;
    // Ray (x, y, 1) meets the plane n·p = n·o at depth z = n·o / n·(x, y, 1).
    const Eigen::Vector3d normal = u.cross(v);
    const double n_dot_o = normal.dot(o);
    const double inv_uu = 1.0 / u.squaredNorm(), inv_vv = 1.0 / v.squaredNorm();
    const double len_u = std::sqrt(u.squaredNorm()), len_v = std::sqrt(v.squaredNorm());
    for (int cy = cy0; cy <= cy1; ++cy) {
      for (int cx = cx0; cx <= cx1; ++cx) {
        const std::size_t cell = static_cast<std::size_t>(cy) * static_cast<std::size_t>(grid_w_) +
                                 static_cast<std::size_t>(cx);
        for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
          const std::uint32_t i = cell_pixels_[k];
          const double x = static_cast<double>(nx_[i]), y = static_cast<double>(ny_[i]);
          const double denom = normal.x() * x + normal.y() * y + normal.z();
          if (std::abs(denom) < 1e-15) continue;
          const double z = n_dot_o / denom;
          if (z <= 1e-6 || z >= static_cast<double>(zbuf_[i])) continue;
          const Eigen::Vector3d local(x * z - o.x(), y * z - o.y(), z - o.z());
          const double a = local.dot(u) * inv_uu, b = local.dot(v) * inv_vv;
          if (a < 0.0 || a > 1.0 || b < 0.0 || b > 1.0) continue;
          zbuf_[i] = static_cast<float>(z);
          quad_of_[i] = static_cast<std::int32_t>(q);
          tex_u_[i] = static_cast<float>(a * len_u);
          tex_v_[i] = static_cast<float>(b * len_v);
        }
      }
    }
  }
  // Texture once per pixel, box-filtered over the footprint (stretched at grazing angles).
  normals_.resize(quads.size());
  for (std::size_t q = 0; q < quads.size(); ++q) {
    normals_[q] = T_cam_world.R * quads[q].edge_u.cross(quads[q].edge_v).normalized();
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (quad_of_[i] < 0) continue;
    const std::size_t q = static_cast<std::size_t>(quad_of_[i]);
    const Quad& quad = quads[q];
    const double x = static_cast<double>(nx_[i]), y = static_cast<double>(ny_[i]);
    const double ray_norm = std::sqrt(x * x + y * y + 1.0);
    const double z = static_cast<double>(zbuf_[i]);
    const Eigen::Vector3d& normal = normals_[q];
    const double cos_incidence = std::abs(normal.x() * x + normal.y() * y + normal.z()) / ray_norm;
    const double footprint = z * ray_norm * pixel_angle_ / std::max(cos_incidence, 0.1);
    out->intensity[i] = static_cast<float>(
        quad.texture.Albedo(static_cast<double>(tex_u_[i]), static_cast<double>(tex_v_[i]),
                            footprint) *
        quad.RadianceAt(t_s));
    out->depth_m[i] = static_cast<float>(z);
  }
}

}  // namespace aavio::sim
