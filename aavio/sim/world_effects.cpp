#include "aavio/sim/world_effects.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "aavio/common/format.hpp"

namespace aavio::sim {

namespace {

constexpr double kLightsPerSecond = 2.0;
constexpr double kSecondsPerMovingObject = 3.0;

/// The path's pose nearest to t_ns.
const geometry::RigidTransform& PoseNear(const std::vector<geometry::StampedPose>& path,
                                         TimeNs t_ns) {
  auto it = std::lower_bound(
      path.begin(), path.end(), t_ns,
      [](const geometry::StampedPose& p, TimeNs t) { return p.t_ns < t; });
  if (it == path.end()) return path.back().T_world_body;
  if (it != path.begin() && t_ns - std::prev(it)->t_ns < it->t_ns - t_ns) --it;
  return it->T_world_body;
}

/// Times spread evenly over the path, `count` of them, at the middles of equal spans.
std::vector<TimeNs> SpreadTimes(const std::vector<geometry::StampedPose>& path, int count) {
  std::vector<TimeNs> times;
  const double span = static_cast<double>(path.back().t_ns - path.front().t_ns);
  for (int k = 0; k < count; ++k)
    times.push_back(path.front().t_ns + static_cast<TimeNs>(span * (k + 0.5) / count));
  return times;
}

Texture MakeTexture(Pattern pattern, double cell_m, double contrast, double mean,
                    std::uint64_t seed) {
  Texture t;
  t.pattern = pattern;
  t.cell_m = cell_m;
  t.contrast = contrast;
  t.mean = mean;
  t.seed = seed;
  return t;
}

int AddFlickeringLights(const WorldEffectPlacement& placement, double flicker_hz,
                        std::mt19937_64* rng, Scene* scene) {
  const std::vector<geometry::StampedPose>& path = placement.camera_path;
  const double seconds = NsToSeconds(path.back().t_ns - path.front().t_ns);
  const int count = std::max(2, static_cast<int>(std::ceil(seconds * kLightsPerSecond)));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double tan_half = std::tan(placement.half_fov_rad);
  std::vector<Quad> lights;
  for (const TimeNs t_ns : SpreadTimes(path, count)) {
    const geometry::RigidTransform& T = PoseNear(path, t_ns);
    // A few tries for a surface in view, facing the camera well enough to be seen.
    for (int attempt = 0; attempt < 8; ++attempt) {
      const Eigen::Vector3d ray_cam((2 * unit(*rng) - 1) * 0.8 * tan_half,
                                    (2 * unit(*rng) - 1) * 0.6 * tan_half, 1.0);
      const Eigen::Vector3d dir = (T.R * ray_cam).normalized();
      Hit hit;
      if (!scene->Intersect(T.t, dir, &hit) || hit.distance > 40.0) continue;
      const Quad& surface = scene->quads()[hit.quad];
      Eigen::Vector3d normal = surface.edge_u.cross(surface.edge_v).normalized();
      if (normal.dot(dir) > 0) normal = -normal;
      if (-normal.dot(dir) < 0.3) continue;  // grazing: barely visible
      const Eigen::Vector3d u = surface.edge_u.normalized(), v = normal.cross(u);
      // 3–10 % of the image wide, 1–4 times as wide as high (tubes, panels, signal heads).
      const double image_width_m = 2.0 * hit.distance * tan_half;
      const double width = std::clamp((0.03 + 0.07 * unit(*rng)) * image_width_m, 0.08, 2.0);
      const double height = width / (1.0 + 3.0 * unit(*rng));
      const bool upright = unit(*rng) < 0.5;
      const Eigen::Vector3d eu = (upright ? v : u) * width, ev = (upright ? u : v) * height;
      const Eigen::Vector3d centre = T.t + hit.distance * dir + 0.01 * normal;
      const double albedo = 0.85 + 0.1 * unit(*rng);
      Quad light{centre - 0.5 * eu - 0.5 * ev, eu, ev,
                 MakeTexture(Pattern::kTiles, 50.0, 0.02, albedo, (*rng)())};
      light.flicker_hz = flicker_hz;
      light.flicker_depth = 0.3 + 0.65 * unit(*rng);
      light.flicker_phase_rad = 2.0 * M_PI / 3.0 * static_cast<double>((*rng)() % 3);
      lights.push_back(light);
      break;
    }
  }
  // Added after the search, so that no light is placed on another.
  for (const Quad& light : lights) scene->AddQuad(light);
  return static_cast<int>(lights.size());
}

/// Distance to the ground below `p` (along gravity), or `fallback_m` if nothing is there.
double GroundBelow(const Scene& scene, const Eigen::Vector3d& p, const Eigen::Vector3d& down,
                   double fallback_m) {
  Hit hit;
  if (scene.Intersect(p, down, &hit) && hit.distance < 5.0) return hit.distance;
  return fallback_m;
}

/// A box standing on the ground (its base `ground_m` below `at_eye_height`, a point at the
/// camera's height), moving at `velocity`; its long side along the motion.
void AddMovingBox(const Eigen::Vector3d& at_eye_height, double ground_m,
                  const Eigen::Vector3d& down, const Eigen::Vector3d& velocity,
                  const Eigen::Vector3d& size, const Texture& texture, double t_since_origin_s,
                  Scene* scene) {
  Eigen::Matrix3d R;
  R.col(0) = velocity.normalized();
  R.col(2) = -down;
  R.col(1) = R.col(2).cross(R.col(0));
  const Eigen::Vector3d centre =
      at_eye_height + (ground_m - 0.5 * size.z()) * down - velocity * t_since_origin_s;
  scene->AddBox({R, centre}, size, {texture}, /*with_bottom=*/false, velocity);
}

int AddMovingObjects(const WorldEffectPlacement& placement, std::mt19937_64* rng, Scene* scene) {
  const std::vector<geometry::StampedPose>& path = placement.camera_path;
  const double seconds = NsToSeconds(path.back().t_ns - path.front().t_ns);
  const int count = std::max(1, static_cast<int>(std::lround(seconds / kSecondsPerMovingObject)));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d down = placement.gravity_world.normalized();
  const double tan_half = std::tan(placement.half_fov_rad);
  struct Pending {
    Eigen::Vector3d at_eye_height, velocity, size;
    double ground_m, t_s;
    Texture texture;
  };
  std::vector<Pending> objects;
  int k = 0;
  for (const TimeNs t_ns : SpreadTimes(path, count)) {
    const geometry::RigidTransform& T = PoseNear(path, t_ns);
    const Eigen::Vector3d forward_raw = T.R.col(2) - T.R.col(2).dot(down) * down;
    if (forward_raw.norm() < 0.3) continue;  // looking up or down: nothing crosses ahead
    const Eigen::Vector3d forward = forward_raw.normalized(), right = down.cross(forward);
    const double t_s = NsToSeconds(t_ns - scene->time_origin_ns);
    // The camera's own speed along its view, over the second around t.
    const Eigen::Vector3d ahead = PoseNear(path, t_ns + kNsPerS / 2).t;
    const Eigen::Vector3d behind = PoseNear(path, t_ns - kNsPerS / 2).t;
    const double camera_speed = std::max(0.0, (ahead - behind).dot(forward));
    Pending o;
    if (placement.street && k % 2 == 0) {
      // An oncoming car in the other lane, 25 m ahead at t.
      const double speed = 8.0 + 6.0 * unit(*rng);
      o.at_eye_height = T.t + 25.0 * forward - 3.2 * right;
      o.velocity = -speed * forward;
      o.size = {4.4, 1.8, 1.5};
      o.texture = MakeTexture(Pattern::kTiles, 0.6, 0.5, 0.4, (*rng)());
    } else if (placement.street) {
      // A cyclist crossing the road ahead, far enough that the car never reaches them.
      const double speed = 4.0 + 2.0 * unit(*rng);
      const double distance = std::max(8.0, 1.3 * camera_speed);
      const double side = unit(*rng) < 0.5 ? 1.0 : -1.0;
      o.at_eye_height = T.t + distance * forward;
      o.velocity = side * speed * right;
      o.size = {1.8, 0.6, 1.7};
      o.texture = MakeTexture(Pattern::kStripes, 0.2, 0.5, 0.35, (*rng)());
    } else {
      // A person walking across the view, a third of the image wide, in front of the scene.
      Hit hit;
      const double free_m = scene->Intersect(T.t, forward, &hit) ? hit.distance : 4.0;
      const double distance = std::max(0.6, std::min(0.76 / tan_half, 0.6 * free_m));
      const double speed = 1.0 + 0.6 * unit(*rng);
      const double side = unit(*rng) < 0.5 ? 1.0 : -1.0;
      o.at_eye_height = T.t + distance * forward;
      o.velocity = side * speed * right;
      o.size = {0.5, 0.3, 1.7};
      o.texture = MakeTexture(Pattern::kStripes, 0.15, 0.5, 0.35, (*rng)());
    }
    o.ground_m = GroundBelow(*scene, o.at_eye_height, down, 1.4);
    o.t_s = t_s;
    objects.push_back(o);
    ++k;
  }
  for (const Pending& o : objects)
    AddMovingBox(o.at_eye_height, o.ground_m, down, o.velocity, o.size, o.texture, o.t_s, scene);
  return static_cast<int>(objects.size());
}

}  // namespace

const std::vector<WorldEffect>& WorldEffects() {
  static const std::vector<WorldEffect> kEffects = {
      {"flicker", "lamps in view flickering at 100 or 120 Hz (mains), modulation 0.3-0.95"},
      {"moving_objects",
       "cars and cyclists in a street, people walking past elsewhere, one every ~3 s"},
  };
  return kEffects;
}

Status CheckWorldEffectNames(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    const auto& all = WorldEffects();
    const auto named = [&](const WorldEffect& e) { return name == e.name; };
    if (std::none_of(all.begin(), all.end(), named)) {
      std::string known;
      for (const WorldEffect& e : all) known += (known.empty() ? "" : ", ") + std::string(e.name);
      return InvalidArgument("unknown world effect '" + name + "' (there are: " + known + ")");
    }
  }
  return Status::Ok();
}

std::string WorldEffectsAdded::Describe() const {
  std::string text;
  if (lights > 0) text += StrFormat("%d flickering lights at %.0f Hz", lights, flicker_hz);
  if (moving_objects > 0)
    text += StrFormat("%s%d moving objects", text.empty() ? "" : ", ", moving_objects);
  return text.empty() ? "none" : text;
}

WorldEffectsAdded AddWorldEffects(const std::vector<std::string>& names,
                                  const WorldEffectPlacement& placement, Scene* scene) {
  WorldEffectsAdded added;
  if (names.empty() || placement.camera_path.size() < 2) return added;
  scene->time_origin_ns = placement.camera_path.front().t_ns;
  // Its own stream, so that switching an effect on leaves the rest of the world as it was.
  std::mt19937_64 rng(placement.seed * 7919 + 5);
  const auto wanted = [&](const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  // Both placements cast rays into the scene as built; lights go first, so that a moving
  // object is never mistaken for a surface to put a lamp on.
  if (wanted("flicker")) {
    added.flicker_hz = rng() % 2 == 0 ? 100.0 : 120.0;
    added.lights = AddFlickeringLights(placement, added.flicker_hz, &rng, scene);
  }
  if (wanted("moving_objects")) {
    scene->Build();
    added.moving_objects = AddMovingObjects(placement, &rng, scene);
  }
  scene->Build();
  return added;
}

}  // namespace aavio::sim
