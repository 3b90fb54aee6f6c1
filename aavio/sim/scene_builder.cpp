#include "aavio/sim/scene_builder.hpp"

#include <cmath>
#include <random>

#include "aavio/geometry/random_draws.hpp"
#include "aavio/sim/furniture.hpp"

namespace aavio::sim {

namespace {

Quad MakeQuad(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
              const Texture& texture) {
  return {origin, u, v, texture};
}

}  // namespace

Scene BuildRoom(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Scene scene;
  const double x0 = -3.0, x1 = 3.0, y_floor = 1.3, y_ceiling = -1.7, z0 = -2.5, z1 = 4.5;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  Texture floor = RandomTexture(rng, 0.15, 0.4);
  floor.pattern = Pattern::kTiles;
  const double height = y_floor - y_ceiling;
  scene.AddQuad(MakeQuad({x0, y_floor, z0}, X * (x1 - x0), Z * (z1 - z0), floor));
  scene.AddQuad(
      MakeQuad({x0, y_ceiling, z0}, X * (x1 - x0), Z * (z1 - z0), RandomTexture(rng, 0.3, 0.8)));
  scene.AddQuad(
      MakeQuad({x0, y_floor, z1}, X * (x1 - x0), -Y * height, RandomTexture(rng, 0.08, 0.3)));
  scene.AddQuad(
      MakeQuad({x0, y_floor, z0}, X * (x1 - x0), -Y * height, RandomTexture(rng, 0.08, 0.3)));
  scene.AddQuad(
      MakeQuad({x0, y_floor, z0}, Z * (z1 - z0), -Y * height, RandomTexture(rng, 0.08, 0.3)));
  scene.AddQuad(
      MakeQuad({x1, y_floor, z0}, Z * (z1 - z0), -Y * height, RandomTexture(rng, 0.08, 0.3)));
  // Posters a few centimetres off the walls.
  for (int k = 0; k < 8; ++k) {
    const double w = 0.4 + 0.8 * unit(rng), h = 0.3 + 0.6 * unit(rng);
    const double x = x0 + 0.5 + (x1 - x0 - 1.0 - w) * unit(rng);
    const double y = y_ceiling + 0.5 + (height - 1.0 - h) * unit(rng);
    scene.AddQuad(MakeQuad({x, y + h, z1 - 0.02}, X * w, -Y * h, RandomTexture(rng, 0.03, 0.12)));
  }
  for (int k = 0; k < 4; ++k) {
    const double w = 0.4 + 0.8 * unit(rng), h = 0.3 + 0.6 * unit(rng);
    const double z = z0 + 1.0 + (z1 - z0 - 2.0 - w) * unit(rng);
    const double y = y_ceiling + 0.5 + (height - 1.0 - h) * unit(rng);
    const double x = (k % 2 == 0) ? x0 + 0.02 : x1 - 0.02;
    scene.AddQuad(MakeQuad({x, y + h, z}, Z * w, -Y * h, RandomTexture(rng, 0.03, 0.12)));
  }
  // Objects on the floor, 0.8–3.6 m ahead of the start.
  for (int k = 0; k < 9; ++k) {
    const Eigen::Vector3d s = geometry::DrawZyx(unit, rng);
    const Eigen::Vector3d size(0.2 + 0.5 * s.x(), 0.2 + 0.5 * s.y(), 0.2 + 0.9 * s.z());
    const Eigen::Vector2d b = geometry::DrawYx(unit, rng);  // x and z on the floor
    const Eigen::Vector3d base(-1.8 + 3.6 * b.x(), y_floor, 0.8 + 2.8 * b.y());
    const double yaw = unit(rng) * M_PI;
    AddStandingBox(&scene, base, -Y, Eigen::Vector3d(std::sin(yaw), 0, std::cos(yaw)), size,
                   {RandomTexture(rng, 0.03, 0.12), RandomTexture(rng, 0.03, 0.12)});
  }
  scene.Build();
  return scene;
}

Scene BuildHall(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Scene scene;
  const double x0 = -10, x1 = 10, y_floor = 1.5, y_ceiling = -6.5, z0 = -10, z1 = 10;
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  const double height = y_floor - y_ceiling;
  scene.AddQuad(
      MakeQuad({x0, y_floor, z0}, X * (x1 - x0), Z * (z1 - z0), RandomTexture(rng, 0.3, 0.8)));
  scene.AddQuad(
      MakeQuad({x0, y_ceiling, z0}, X * (x1 - x0), Z * (z1 - z0), RandomTexture(rng, 0.5, 1.5)));
  scene.AddQuad(
      MakeQuad({x0, y_floor, z1}, X * (x1 - x0), -Y * height, RandomTexture(rng, 0.2, 0.8)));
  scene.AddQuad(
      MakeQuad({x0, y_floor, z0}, X * (x1 - x0), -Y * height, RandomTexture(rng, 0.2, 0.8)));
  scene.AddQuad(
      MakeQuad({x0, y_floor, z0}, Z * (z1 - z0), -Y * height, RandomTexture(rng, 0.2, 0.8)));
  scene.AddQuad(
      MakeQuad({x1, y_floor, z0}, Z * (z1 - z0), -Y * height, RandomTexture(rng, 0.2, 0.8)));
  for (int k = 0; k < 6; ++k) {                             // pillars
    const Eigen::Vector2d b = geometry::DrawYx(unit, rng);  // x and z on the floor
    const Eigen::Vector3d base(-8 + 16 * b.x(), y_floor, -8 + 16 * b.y());
    if (std::hypot(base.x(), base.z()) < 3.0) continue;  // keep the take-off area clear
    AddStandingBox(&scene, base, -Y, Z, {0.6, 0.6, height}, {RandomTexture(rng, 0.1, 0.4)});
  }
  for (int k = 0; k < 14; ++k) {                            // crates and nets
    const Eigen::Vector2d b = geometry::DrawYx(unit, rng);  // x and z on the floor
    const Eigen::Vector3d base(-8 + 16 * b.x(), y_floor, -8 + 16 * b.y());
    if (std::hypot(base.x(), base.z()) < 2.5) continue;
    const Eigen::Vector3d s = geometry::DrawZyx(unit, rng);
    const Eigen::Vector3d size(0.5 + 1.5 * s.x(), 0.5 + 1.5 * s.y(), 0.4 + 2.0 * s.z());
    const double yaw = unit(rng) * M_PI;
    AddStandingBox(&scene, base, -Y, Eigen::Vector3d(std::sin(yaw), 0, std::cos(yaw)), size,
                   {RandomTexture(rng, 0.05, 0.3), RandomTexture(rng, 0.05, 0.3)});
  }
  scene.Build();
  return scene;
}

Scene BuildOffice(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Scene scene;
  const double y_floor = 1.0;  // the camera is held about a metre above the floor
  AddRoomShell(&scene, rng, {-2.5, -1.6, -2.0}, {2.5, y_floor, 2.4}, 9);
  // The desk the camera looks at, its monitor and clutter; 0.7–1.5 m ahead.
  const double desk_top =
      y_floor - AddTable(&scene, rng, {0.0, y_floor, 1.1}, 0.0, {1.6, 0.8, 0.74}, 8);
  AddMonitor(&scene, rng, {0.3 * (unit(rng) - 0.5), desk_top, 1.35}, 0.0);
  // Bookshelves against the wall behind the desk, a side table and a cabinet.
  for (double x : {-1.6, 1.6}) {
    AddShelf(&scene, rng, {x, y_floor, 2.15}, 0.0, {0.9, 0.35, 1.9}, 5);
  }
  AddTable(&scene, rng, {1.9, y_floor, 0.6}, -M_PI / 2, {1.2, 0.6, 0.74}, 5);
  AddStandingBox(&scene, {-1.95, y_floor, 1.0}, -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX(),
                 {0.6, 0.5, 1.1}, {RandomTexture(rng, 0.05, 0.2), RandomTexture(rng, 0.02, 0.1)});
  scene.Build();
  return scene;
}

Scene BuildLab(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Scene scene;
  const double y_floor = 1.3;
  const Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
  AddRoomShell(&scene, rng, {-3.5, -1.7, -2.5}, {3.5, y_floor, 3.5}, 10);
  // A workbench ahead, a robot arm on its own table, a sofa along the left wall, shelves along
  // the far wall, a cabinet and crates: the furniture of a mocap lab.
  AddTable(&scene, rng, {0.2, y_floor, 1.4}, 0.0, {1.6, 0.8, 0.9}, 8);
  const double arm_table = AddTable(&scene, rng, {-0.9, y_floor, 2.1}, 0.0, {0.8, 0.8, 0.75}, 2);
  AddRobotArm(&scene, rng, {-0.9, y_floor - arm_table, 2.1}, M_PI * (unit(rng) - 0.5));
  AddSofa(&scene, rng, {-3.05, y_floor, 0.6}, -M_PI / 2);
  for (double x : {-2.2, 2.2}) {
    AddShelf(&scene, rng, {x, y_floor, 3.25}, 0.0, {1.0, 0.4, 2.0}, 5);
  }
  AddStandingBox(&scene, {3.15, y_floor, 1.2}, up, Eigen::Vector3d::UnitX(), {0.8, 0.6, 1.2},
                 {RandomTexture(rng, 0.05, 0.2), RandomTexture(rng, 0.02, 0.1)});
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d s = geometry::DrawZyx(unit, rng);
    const Eigen::Vector3d size(0.3 + 0.4 * s.x(), 0.3 + 0.4 * s.y(), 0.2 + 0.4 * s.z());
    const Eigen::Vector2d b = geometry::DrawYx(unit, rng);  // x and z on the floor
    const Eigen::Vector3d base(1.2 + 1.6 * b.x(), y_floor, 2.0 + 0.8 * b.y());
    const double yaw = unit(rng) * M_PI;
    AddStandingBox(&scene, base, up, Eigen::Vector3d(std::sin(yaw), 0, std::cos(yaw)), size,
                   {RandomTexture(rng, 0.03, 0.12), RandomTexture(rng, 0.03, 0.12)});
  }
  scene.Build();
  return scene;
}

Scene BuildStreet(const std::vector<geometry::StampedPose>& path, const Eigen::Vector3d& down_in,
                  double camera_height_m, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d down = down_in.normalized();
  const Eigen::Vector3d up = -down;
  // Ground points under the camera, every ~10 m of travel, extended 40 m past both ends.
  std::vector<Eigen::Vector3d> ground;
  for (const geometry::StampedPose& p : path) {
    const Eigen::Vector3d g = p.T_world_body.t + down * camera_height_m;
    if (ground.empty() || (g - ground.back()).norm() >= 10.0) ground.push_back(g);
  }
  if (ground.size() < 2) {  // standing still: a street along the camera's view
    const Eigen::Vector3d forward = path.front().T_world_body.R.col(2);
    ground = {ground.front(),
              ground.front() + (forward - forward.dot(down) * down).normalized() * 10.0};
  }
  auto horizontal = [&](Eigen::Vector3d v) { return (v - v.dot(down) * down).normalized(); };
  const Eigen::Vector3d first_dir = horizontal(ground[1] - ground[0]);
  const Eigen::Vector3d last_dir = horizontal(ground.back() - ground[ground.size() - 2]);
  std::vector<Eigen::Vector3d> extended;
  extended.reserve(ground.size() + 2);
  extended.push_back(ground.front() - first_dir * 40.0);
  for (const Eigen::Vector3d& g : ground)
    extended.push_back(g);
  extended.push_back(ground.back() + last_dir * 40.0);
  ground.swap(extended);

  Scene scene;
  Texture road;
  road.pattern = Pattern::kTiles;
  road.cell_m = 1.2;
  road.contrast = 0.35;
  road.mean = 0.35;
  for (std::size_t i = 0; i + 1 < ground.size(); ++i) {
    const Eigen::Vector3d a = ground[i], b = ground[i + 1];
    const Eigen::Vector3d along = b - a;
    const Eigen::Vector3d f = horizontal(along);
    const Eigen::Vector3d right = down.cross(f);  // camera x: y × z
    road.seed = rng();
    road.angle_rad = 0.3 * (unit(rng) - 0.5);
    scene.AddQuad(MakeQuad(a - right * 8.0, right * 16.0, along, road));
    for (double side : {-1.0, 1.0}) {
      // Facade: windows in rows (horizontal sills and ledges) or bricks; 6–15 m away.
      const double distance = 6.0 + 9.0 * unit(rng);
      const double height = 8.0 + 12.0 * unit(rng);
      Texture facade;
      facade.pattern = unit(rng) < 0.7 ? Pattern::kWindows : Pattern::kBricks;
      facade.cell_m =
          facade.pattern == Pattern::kWindows ? 1.0 + 0.8 * unit(rng) : 0.25 + 0.2 * unit(rng);
      facade.contrast = 0.5 + 0.4 * unit(rng);
      facade.mean = 0.35 + 0.3 * unit(rng);
      facade.seed = rng();
      const Eigen::Vector3d base = a + right * side * distance;
      // u along the street, v up: facade patterns are level with the ground.
      scene.AddQuad(MakeQuad(base, along, up * height, facade));
      // A ledge band part-way up: a strong horizontal edge.
      Texture ledge = RandomTexture(rng, 0.2, 0.5);
      ledge.pattern = Pattern::kStripes;
      ledge.angle_rad = 0.0;
      const double ledge_at = 3.0 + 2.0 * unit(rng);
      scene.AddQuad(MakeQuad(base - right * side * 0.05 + up * ledge_at, along, up * 0.4, ledge));
      // Poles at the kerb and parked cars.
      if (unit(rng) < 0.7) {
        AddStandingBox(&scene, a + along * unit(rng) + right * side * 4.5, up, f, {0.15, 0.15, 5.0},
                       {RandomTexture(rng, 0.05, 0.2)});
      }
      if (unit(rng) < 0.5) {
        AddStandingBox(&scene, a + along * (0.2 + 0.6 * unit(rng)) + right * side * 3.3, up, f,
                       {1.8, 4.2, 1.5},
                       {RandomTexture(rng, 0.1, 0.4), RandomTexture(rng, 0.1, 0.4)});
      }
    }
  }
  scene.sky_albedo = 0.8;
  scene.Build();
  return scene;
}

Scene BuildPlanes(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                        Z = Eigen::Vector3d::UnitZ();
  // Coarse, low-contrast patterns: few edges, and weak ones.
  auto sparse = [&](double cell_lo, double cell_hi) {
    Texture t = RandomTexture(rng, cell_lo, cell_hi);
    t.contrast = 0.25 + 0.25 * unit(rng);
    return t;
  };
  Scene scene;
  const double y_floor = 1.0, y_top = -2.0, z_wall = 3.5;
  scene.AddQuad(
      MakeQuad({-4.0, y_floor, z_wall}, X * 8.0, -Y * (y_floor - y_top), sparse(0.35, 0.6)));
  scene.AddQuad(MakeQuad({-4.0, y_floor, -1.0}, X * 8.0, Z * (z_wall + 1.0), sparse(0.3, 0.6)));
  // Two panels standing on the floor, turned up to ±30° towards the camera.
  for (int k = 0; k < 2; ++k) {
    const double w = 0.8 + 0.4 * unit(rng), h = 1.2 + 0.5 * unit(rng);
    const double x = (k == 0 ? -1.3 : 0.4) + 0.3 * unit(rng), z = 1.6 + 1.0 * unit(rng);
    const double yaw = (k == 0 ? 1.0 : -1.0) * (0.2 + 0.3 * unit(rng));
    const Eigen::Vector3d across(std::cos(yaw), 0.0, std::sin(yaw));
    scene.AddQuad(MakeQuad({x, y_floor, z}, across * w, -Y * h, sparse(0.25, 0.45)));
  }
  scene.sky_albedo = 0.5;
  scene.Build();
  return scene;
}

Scene BuildScene(SceneKind kind, const std::vector<geometry::StampedPose>& path,
                 const Eigen::Vector3d& down, double camera_height_m, std::uint64_t seed) {
  switch (kind) {
    case SceneKind::kOffice:
      return BuildOffice(seed);
    case SceneKind::kLab:
      return BuildLab(seed);
    case SceneKind::kHall:
      return BuildHall(seed);
    case SceneKind::kStreet:
      return BuildStreet(path, down, camera_height_m, seed);
    case SceneKind::kPlanes:
      return BuildPlanes(seed);
    case SceneKind::kRoom:
      break;
  }
  return BuildRoom(seed);
}

}  // namespace aavio::sim
