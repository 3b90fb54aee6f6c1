#include "aavio/sim/furniture.hpp"

#include <cmath>

#include "aavio/geometry/random_draws.hpp"

namespace aavio::sim {

namespace {

const Eigen::Vector3d kUp = -Eigen::Vector3d::UnitY();  // the canonical frame's y points down

Eigen::Vector3d Forward(double yaw_rad) {
  return {std::sin(yaw_rad), 0.0, std::cos(yaw_rad)};
}
Eigen::Vector3d Right(double yaw_rad) {
  return Forward(yaw_rad).cross(kUp);
}

/// Small objects of an office or lab: books, boxes, mugs; random footprint on a surface of
/// `width` × `depth` centred at `centre` (a point on the surface).
void AddClutter(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& centre, double yaw_rad,
                double width, double depth, int count) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d f = Forward(yaw_rad), r = Right(yaw_rad);
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d s = geometry::DrawZyx(unit, rng);
    const Eigen::Vector3d size(0.05 + 0.25 * s.x(), 0.05 + 0.2 * s.y(), 0.03 + 0.25 * s.z());
    const Eigen::Vector2d p = geometry::DrawYx(unit, rng);  // across (x) and along (y) the shelf
    const Eigen::Vector3d at =
        centre + r * (p.x() - 0.5) * (width - size.x()) + f * (p.y() - 0.5) * (depth - size.y());
    const double turn = yaw_rad + 0.6 * (unit(rng) - 0.5);
    AddStandingBox(scene, at, kUp, Forward(turn), size,
                   {RandomTexture(rng, 0.01, 0.06), RandomTexture(rng, 0.01, 0.06)});
  }
}

}  // namespace

Texture RandomTexture(std::mt19937_64& rng, double cell_lo, double cell_hi) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Texture t;
  const double pick = unit(rng);
  t.pattern = pick < 0.25   ? Pattern::kBricks
              : pick < 0.5  ? Pattern::kTiles
              : pick < 0.75 ? Pattern::kBlobs
                            : Pattern::kStripes;
  t.cell_m = cell_lo * std::pow(cell_hi / cell_lo, unit(rng));
  const bool level = t.pattern == Pattern::kBricks || unit(rng) < 0.3;
  t.angle_rad = level ? 0.0 : unit(rng) * M_PI;
  t.contrast = 0.5 + 0.4 * unit(rng);
  t.mean = 0.35 + 0.3 * unit(rng);
  t.seed = rng();
  return t;
}

void AddStandingBox(Scene* scene, const Eigen::Vector3d& base_centre, const Eigen::Vector3d& up,
                    const Eigen::Vector3d& forward, const Eigen::Vector3d& size,
                    const std::vector<Texture>& textures) {
  Eigen::Matrix3d R;
  R.col(2) = up.normalized();
  R.col(1) = forward.normalized();
  R.col(0) = R.col(1).cross(R.col(2));
  scene->AddBox({R, base_centre + up.normalized() * size.z() / 2.0}, size, textures, false);
}

void AddRoomShell(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& lo,
                  const Eigen::Vector3d& hi, int posters) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  const double x0 = lo.x(), x1 = hi.x(), y_ceiling = lo.y(), y_floor = hi.y(), z0 = lo.z(),
               z1 = hi.z();
  const double height = y_floor - y_ceiling;
  Texture floor = RandomTexture(rng, 0.15, 0.4);
  floor.pattern = Pattern::kTiles;
  scene->AddQuad(Quad{{x0, y_floor, z0}, X * (x1 - x0), Z * (z1 - z0), floor});
  scene->AddQuad(
      Quad{{x0, y_ceiling, z0}, X * (x1 - x0), Z * (z1 - z0), RandomTexture(rng, 0.3, 0.8)});
  scene->AddQuad(
      Quad{{x0, y_floor, z1}, X * (x1 - x0), -Y * height, RandomTexture(rng, 0.08, 0.3)});
  scene->AddQuad(
      Quad{{x0, y_floor, z0}, X * (x1 - x0), -Y * height, RandomTexture(rng, 0.08, 0.3)});
  scene->AddQuad(
      Quad{{x0, y_floor, z0}, Z * (z1 - z0), -Y * height, RandomTexture(rng, 0.08, 0.3)});
  scene->AddQuad(
      Quad{{x1, y_floor, z0}, Z * (z1 - z0), -Y * height, RandomTexture(rng, 0.08, 0.3)});
  // Pictures on the front wall (two in three) and the side walls.
  for (int k = 0; k < posters; ++k) {
    const double w = 0.4 + 0.8 * unit(rng), h = 0.3 + 0.6 * unit(rng);
    const double y = y_ceiling + 0.4 + (height - 0.8 - h) * unit(rng);
    const Texture texture = RandomTexture(rng, 0.03, 0.12);
    if (k % 3 != 2) {
      const double x = x0 + 0.5 + (x1 - x0 - 1.0 - w) * unit(rng);
      scene->AddQuad(Quad{{x, y + h, z1 - 0.02}, X * w, -Y * h, texture});
    } else {
      const double z = z0 + 0.5 + (z1 - z0 - 1.0 - w) * unit(rng);
      const double x = (k / 3) % 2 == 0 ? x0 + 0.02 : x1 - 0.02;
      scene->AddQuad(Quad{{x, y + h, z}, Z * w, -Y * h, texture});
    }
  }
}

double AddTable(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad,
                const Eigen::Vector3d& size, int items) {
  const Eigen::Vector3d f = Forward(yaw_rad), r = Right(yaw_rad);
  const double top = 0.035, leg = 0.05;
  const Texture wood = RandomTexture(rng, 0.02, 0.1), metal = RandomTexture(rng, 0.05, 0.2);
  AddStandingBox(scene, base + kUp * (size.z() - top), kUp, f, {size.x(), size.y(), top}, {wood});
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      const Eigen::Vector3d at =
          base + r * sx * (size.x() / 2 - leg) + f * sy * (size.y() / 2 - leg);
      AddStandingBox(scene, at, kUp, f, {leg, leg, size.z() - top}, {metal});
    }
  }
  AddClutter(scene, rng, base + kUp * size.z(), yaw_rad, size.x() - 0.1, size.y() - 0.1, items);
  return size.z();
}

void AddShelf(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad,
              const Eigen::Vector3d& size, int levels) {
  const Eigen::Vector3d f = Forward(yaw_rad), r = Right(yaw_rad);
  const double board = 0.025;
  const Texture panel = RandomTexture(rng, 0.02, 0.1);
  for (double side : {-1.0, 1.0}) {
    AddStandingBox(scene, base + r * side * (size.x() - board) / 2, kUp, f,
                   {board, size.y(), size.z()}, {panel});
  }
  AddStandingBox(scene, base + f * (size.y() - board) / 2, kUp, f, {size.x(), board, size.z()},
                 {RandomTexture(rng, 0.05, 0.2)});
  for (int k = 0; k < levels; ++k) {
    const double h = size.z() * k / std::max(1, levels - 1) - (k == levels - 1 ? board : 0.0);
    const Eigen::Vector3d at = base + kUp * h;
    AddStandingBox(scene, at, kUp, f, {size.x() - 2 * board, size.y() - board, board}, {panel});
    if (k < levels - 1) {
      AddClutter(scene, rng, at + kUp * board, yaw_rad, size.x() - 0.1, size.y() - 0.1, 4);
    }
  }
}

void AddSofa(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad) {
  const Eigen::Vector3d f = Forward(yaw_rad), r = Right(yaw_rad);
  const std::vector<Texture> fabric = {RandomTexture(rng, 0.05, 0.2),
                                       RandomTexture(rng, 0.05, 0.2)};
  const double width = 1.9, depth = 0.85;
  AddStandingBox(scene, base, kUp, f, {width, depth, 0.42}, fabric);
  AddStandingBox(scene, base + f * (depth / 2 - 0.1), kUp, f, {width, 0.2, 0.85}, fabric);
  for (double side : {-1.0, 1.0}) {
    AddStandingBox(scene, base + r * side * (width / 2 - 0.1), kUp, f, {0.2, depth, 0.62}, fabric);
  }
  // Cushions.
  for (double at : {-0.45, 0.45}) {
    AddStandingBox(scene, base + r * at + f * 0.1 + kUp * 0.42, kUp, f, {0.45, 0.15, 0.4},
                   {RandomTexture(rng, 0.02, 0.08)});
  }
}

void AddMonitor(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad) {
  const Eigen::Vector3d f = Forward(yaw_rad);
  const Texture dark = RandomTexture(rng, 0.02, 0.05);
  AddStandingBox(scene, base, kUp, f, {0.2, 0.18, 0.015}, {dark});
  AddStandingBox(scene, base + f * 0.04, kUp, f, {0.05, 0.03, 0.15}, {dark});
  // The screen shows a picture: a fine texture on its front face.
  AddStandingBox(scene, base + kUp * 0.12, kUp, f, {0.6, 0.04, 0.36},
                 {RandomTexture(rng, 0.01, 0.05), dark});
}

void AddRobotArm(Scene* scene, std::mt19937_64& rng, const Eigen::Vector3d& base, double yaw_rad) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d f = Forward(yaw_rad);
  const Texture paint = RandomTexture(rng, 0.03, 0.1), joint = RandomTexture(rng, 0.01, 0.04);
  AddStandingBox(scene, base, kUp, f, {0.22, 0.22, 0.12}, {joint});
  AddStandingBox(scene, base + kUp * 0.12, kUp, f, {0.11, 0.11, 0.45}, {paint});
  // Forearm from the shoulder, tilted forward and down by a random angle.
  const Eigen::Vector3d shoulder = base + kUp * 0.57;
  const double tilt = 0.5 + 0.8 * unit(rng), length = 0.4;
  const Eigen::Vector3d along = (std::cos(tilt) * kUp + std::sin(tilt) * f).normalized();
  Eigen::Matrix3d R;
  R.col(2) = along;
  R.col(1) = Right(yaw_rad).cross(along).normalized();
  R.col(0) = R.col(1).cross(R.col(2));
  scene->AddBox({R, shoulder + along * length / 2}, {0.08, 0.08, length}, {paint});
  scene->AddBox({R, shoulder + along * (length + 0.04)}, {0.14, 0.05, 0.08}, {joint});
}

}  // namespace aavio::sim
