#include "aavio/sim/simulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "aavio/common/format.hpp"
#include "aavio/io/calibration.hpp"
#include "aavio/io/config_yaml.hpp"
#include "aavio/io/output_folder.hpp"
#include "aavio/io/sequence.hpp"
#include "aavio/io/sequence_writer.hpp"
#include "aavio/io/trajectory_io.hpp"
#include "aavio/sim/edge_truth.hpp"
#include "aavio/sim/event_simulation.hpp"
#include "aavio/sim/imu_synthesis.hpp"
#include "aavio/sim/motion_spline.hpp"
#include "aavio/sim/motions.hpp"
#include "aavio/sim/presets.hpp"
#include "aavio/sim/recorded_motion.hpp"
#include "aavio/sim/renderer.hpp"
#include "aavio/sim/scene_builder.hpp"

namespace aavio::sim {

namespace fs = std::filesystem;

namespace {

// Removes the events of the dark and camera-off stretches.
void DropDisturbedEvents(const std::vector<Disturbance>& disturbances, TimeNs t_begin,
                         std::vector<events::Event> batch[2]) {
  for (const Disturbance& d : disturbances) {
    if (d.kind != Disturbance::Kind::kDark && d.kind != Disturbance::Kind::kRightOff) continue;
    for (int side = d.kind == Disturbance::Kind::kDark ? 0 : 1; side < 2; ++side) {
      std::erase_if(batch[side], [&](const events::Event& e) {
        return d.Covers(NsToSeconds(e.t_ns - t_begin));
      });
    }
  }
}

// What a simulated sequence folder holds: a sequence, its calibration(s), scene and previews.
std::vector<const char*> SimulationOutputs() {
  std::vector<const char*> names(std::begin(io::kSequenceOutputs), std::end(io::kSequenceOutputs));
  names.insert(names.end(), {"calibration", "calibration_true", "scene.txt", "depth", "preview"});
  return names;
}

Status WriteScene(const std::string& path, const Scene& scene) {
  std::string text =
      "# quads: origin(3) edge_u(3) edge_v(3) pattern cell_m angle_rad contrast mean seed"
      " velocity_mps(3) flicker_hz flicker_depth flicker_phase_rad\n"
      "# a moving quad's origin is where it is at the first pose's time\n";
  for (const Quad& q : scene.quads()) {
    text += StrFormat(
        "%.6f %.6f %.6f %.6f %.6f %.6f %.6f %.6f %.6f %d %.6f %.6f %.4f %.4f %llu %.4f %.4f %.4f "
        "%.1f %.3f %.4f\n",
        q.origin.x(), q.origin.y(), q.origin.z(), q.edge_u.x(), q.edge_u.y(), q.edge_u.z(),
        q.edge_v.x(), q.edge_v.y(), q.edge_v.z(), static_cast<int>(q.texture.pattern),
        q.texture.cell_m, q.texture.angle_rad, q.texture.contrast, q.texture.mean,
        static_cast<unsigned long long>(q.texture.seed), q.velocity_mps.x(), q.velocity_mps.y(),
        q.velocity_mps.z(), q.flicker_hz, q.flicker_depth, q.flicker_phase_rad);
  }
  return io::WriteTextFile(path, text);
}

cv::Mat EventFrame(const std::vector<events::Event>& events, int width, int height) {
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  for (const events::Event& e : events) {
    image.at<cv::Vec3b>(e.y, e.x) = e.polarity ? cv::Vec3b(200, 60, 0) : cv::Vec3b(0, 0, 220);
  }
  return image;
}

cv::Mat DepthColour(const std::vector<float>& depth, int width, int height) {
  cv::Mat inv(height, width, CV_8UC1, cv::Scalar(0));
  float lo = 1e9f, hi = 0.0f;
  for (float d : depth) {
    if (d > 0.0f) {
      lo = std::min(lo, 1.0f / d);
      hi = std::max(hi, 1.0f / d);
    }
  }
  for (int i = 0; i < width * height; ++i) {
    if (depth[i] > 0.0f && hi > lo) {
      inv.data[i] = static_cast<std::uint8_t>(255.0f * (1.0f / depth[i] - lo) / (hi - lo));
    }
  }
  cv::Mat colour;
  cv::applyColorMap(inv, colour, cv::COLORMAP_JET);  // red near, blue far
  for (int i = 0; i < width * height; ++i) {
    if (depth[i] <= 0.0f) colour.at<cv::Vec3b>(i / width, i % width) = cv::Vec3b(0, 0, 0);
  }
  return colour;
}

cv::Mat TopView(const Scene& scene, const std::vector<geometry::StampedPose>& path,
                const geometry::RigidTransform& T_world_canonical) {
  // Project onto the level plane of the canonical frame (x right, z forward).
  const geometry::RigidTransform T = T_world_canonical.Inverse();
  std::vector<cv::Point2d> points;
  for (const auto& p : path) {
    const Eigen::Vector3d c = T * p.T_world_body.t;
    points.emplace_back(c.x(), c.z());
  }
  // The path's bounding box with a margin that shows the scene around it: 4 m for a room,
  // up to 15 m (a street canyon's facades) for long paths.
  double x0 = 0, x1 = 0, z0 = 0, z1 = 0;
  for (const cv::Point2d& p : points) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    z0 = std::min(z0, p.y), z1 = std::max(z1, p.y);
  }
  const double margin = std::clamp(0.3 * std::max(x1 - x0, z1 - z0), 4.0, 15.0);
  x0 -= margin, x1 += margin, z0 -= margin, z1 += margin;
  const double scale = 800.0 / std::max(x1 - x0, z1 - z0);
  auto px = [&](double x, double z) {
    return cv::Point(static_cast<int>((x - x0) * scale), static_cast<int>((z1 - z) * scale));
  };
  cv::Mat image(static_cast<int>((z1 - z0) * scale) + 1, static_cast<int>((x1 - x0) * scale) + 1,
                CV_8UC3, cv::Scalar(255, 255, 255));
  for (const Quad& q : scene.quads()) {
    const Eigen::Vector3d a = T * q.origin, b = T * (q.origin + q.edge_u),
                          c = T * (q.origin + q.edge_v);
    cv::line(image, px(a.x(), a.z()), px(b.x(), b.z()), cv::Scalar(120, 120, 120), 1);
    cv::line(image, px(a.x(), a.z()), px(c.x(), c.z()), cv::Scalar(120, 120, 120), 1);
  }
  for (std::size_t i = 1; i < points.size(); ++i) {
    cv::line(image, px(points[i - 1].x, points[i - 1].y), px(points[i].x, points[i].y),
             cv::Scalar(0, 0, 230), 2);
  }
  return image;
}

// Ground-truth depth of the rectified left camera at a fixed rate: DSEC-style disparity PNGs,
// float depth TIFFs and edge labels, with their timestamps.
class DepthTruthWriter {
 public:
  DepthTruthWriter(const SimulationWorld& world, const fs::path& out, bool preview)
      : world_(world),
        renderer_(*geometry::CameraModel::Create(RectifiedLeft(world.rig))),
        folder_(out / "depth"),
        preview_(preview ? out / "preview" / "gt_depth.png" : fs::path()) {}

  Status Write(TimeNs t) {
    const geometry::StereoRig& rig = world_.rig;
    RenderedImage d;
    renderer_.Render(world_.scene, world_.spline.Pose(t), t, &d);
    cv::Mat disparity(rig.height(), rig.width(), CV_16UC1, cv::Scalar(0));
    cv::Mat depth(rig.height(), rig.width(), CV_32FC1, cv::Scalar(0));
    const double offset = rig.cx_left() - rig.cx_right();
    for (int i = 0; i < rig.width() * rig.height(); ++i) {
      const float z = d.depth_m[i];
      if (z <= 0.0f) continue;
      depth.at<float>(i / rig.width(), i % rig.width()) = z;
      const double disp = rig.focal_px() * rig.baseline_m() / static_cast<double>(z) + offset;
      if (disp > 0.0 && disp * 256.0 < 65535.0) {
        disparity.at<std::uint16_t>(i / rig.width(), i % rig.width()) =
            static_cast<std::uint16_t>(std::lround(disp * 256.0));
      }
    }
    const std::string index = StrFormat("%06lld", static_cast<long long>(count_));
    if (!cv::imwrite((folder_ / ("disparity_" + index + ".png")).string(), disparity) ||
        !cv::imwrite((folder_ / ("depth_" + index + ".tiff")).string(), depth) ||
        !cv::imwrite((folder_ / ("edges_" + index + ".png")).string(),
                     EdgeLabels(d, EdgeTruthConfig{}))) {
      return IoError(folder_.string() + ": cannot write the ground-truth maps");
    }
    if (!preview_.empty() && count_ == 0)
      cv::imwrite(preview_.string(), DepthColour(d.depth_m, rig.width(), rig.height()));
    stamps_ += FormatSecondsNs(t) + " " + index + "\n";
    ++count_;
    return Status::Ok();
  }
  /// Writes the timestamps; returns how many maps were written.
  Expected<std::int64_t> Finish() {
    AAVIO_RETURN_IF_ERROR(io::WriteTextFile((folder_ / "timestamps.txt").string(), stamps_));
    return count_;
  }

 private:
  static geometry::CameraIntrinsics RectifiedLeft(const geometry::StereoRig& rig) {
    return {rig.width(),
            rig.height(),
            rig.focal_px(),
            rig.focal_px(),
            rig.cx_left(),
            rig.cy(),
            geometry::DistortionModel::kNone,
            {}};
  }

  const SimulationWorld& world_;
  const Renderer renderer_;
  fs::path folder_;
  fs::path preview_;
  std::string stamps_ = "# t[s] index\n";
  std::int64_t count_ = 0;
};

// The folder, the calibration the odometry is given (the true rig, or the rig with the sensor's
// calibration errors, then with the true one beside it for reference) and the scene.
Status PrepareFolder(const SimulationRequest& request, const SimulationWorld& world) {
  const fs::path out(request.out_dir);
  const std::vector<const char*> outputs = SimulationOutputs();
  AAVIO_RETURN_IF_ERROR(io::PrepareOutputFolder(
      request.out_dir, {.outputs = outputs, .overwrite = request.overwrite}));
  std::error_code ec;
  fs::create_directories(out / "depth", ec);
  if (ec) return IoError(request.out_dir + ": cannot create the folder (" + ec.message() + ")");
  const std::string name = "aavio_" + world.preset.name;
  AAVIO_RETURN_IF_ERROR(
      io::WriteEsvoCalibration((out / "calibration").string(), world.calibration_rig, name));
  if (world.sensor.rig.PerturbsCalibration()) {
    AAVIO_RETURN_IF_ERROR(
        io::WriteEsvoCalibration((out / "calibration_true").string(), world.rig, name + "_true"));
  }
  AAVIO_RETURN_IF_ERROR(WriteScene((out / "scene.txt").string(), world.scene));
  if (request.preview) fs::create_directories(out / "preview");
  return Status::Ok();
}

// What the event loop gathers beside the files.
struct EventTally {
  std::vector<std::int64_t> pixel_counts;  // left camera
  std::vector<events::Event> preview[2];   // 20 ms around the middle
};

// Streams both cameras' events to `sink`, and the ground-truth depth maps between them.
Status WriteEvents(const SimulationRequest& request, const SimulationWorld& world,
                   StereoEventSimulation* simulation, io::SequenceWriter* sink,
                   DepthTruthWriter* depth, const std::function<void(double)>& progress,
                   SimulationReport* report, EventTally* tally) {
  const geometry::StereoRig& rig = world.rig;
  const TimeNs t_begin = world.spline.t_begin_ns(), t_end = world.spline.t_end_ns();
  tally->pixel_counts.assign(static_cast<std::size_t>(rig.width()) * rig.height(), 0);
  const TimeNs depth_step = SecondsToNs(1.0 / world.preset.depth_rate_hz);
  TimeNs next_depth = t_begin;
  // The right camera's clock runs ahead of the left's by the rig's offset.
  const TimeNs right_clock_offset_ns =
      static_cast<TimeNs>(std::llround(world.sensor.rig.right_clock_offset_us * 1e3));
  const TimeNs preview_at = t_begin + (t_end - t_begin) / 2;
  std::vector<events::Event> batch[2];
  TimeNs t = t_begin;
  while (t < t_end) {
    batch[0].clear();
    batch[1].clear();
    const TimeNs t_next = simulation->Step(t_end, &batch[0], &batch[1]);
    for (events::Event& e : batch[1])
      e.t_ns += right_clock_offset_ns;
    DropDisturbedEvents(request.disturbances, t_begin, batch);
    for (int side = 0; side < 2; ++side)
      AAVIO_RETURN_IF_ERROR(sink->WriteEvents(side == 0, batch[side]));
    for (const events::Event& e : batch[0])
      ++tally->pixel_counts[static_cast<std::size_t>(e.y) * rig.width() + e.x];
    report->events_left += static_cast<std::int64_t>(batch[0].size());
    report->events_right += static_cast<std::int64_t>(batch[1].size());
    if (request.preview && t_next > preview_at - 20 * kNsPerMs && t <= preview_at) {
      for (int side = 0; side < 2; ++side) {
        tally->preview[side].insert(tally->preview[side].end(), batch[side].begin(),
                                    batch[side].end());
      }
    }
    while (next_depth <= t_next) {
      AAVIO_RETURN_IF_ERROR(depth->Write(next_depth));
      next_depth += depth_step;
    }
    ++report->render_steps;
    t = t_next;
    if (progress) progress(NsToSeconds(t - t_begin) / std::max(1e-9, NsToSeconds(t_end - t_begin)));
  }
  return Status::Ok();
}

// The IMU through the extrinsic (identity if the calibration has none), on its own clock, and
// the ground-truth poses; returns the poses.
Expected<std::vector<geometry::StampedPose>> WriteImuAndPoses(const SimulationRequest& request,
                                                              const SimulationWorld& world,
                                                              io::SequenceWriter* sink,
                                                              SimulationReport* report) {
  const MotionSpline& spline = world.spline;
  const geometry::RigidTransform T_imu_rect =
      world.rig.T_imu_rect_left().value_or(geometry::RigidTransform());
  Expected<std::vector<imu::ImuSample>> imu = SynthesizeImu(
      spline, T_imu_rect, world.motion.gravity_world, world.preset.imu, request.seed * 2 + 13);
  if (!imu) return imu.status();
  const TimeNs imu_offset_ns =
      static_cast<TimeNs>(std::llround(world.sensor.rig.imu_time_offset_ms * 1e6));
  for (imu::ImuSample& sample : *imu)
    sample.t_ns += imu_offset_ns;
  std::vector<geometry::StampedPose> gt;
  const TimeNs pose_step = SecondsToNs(1.0 / world.preset.pose_rate_hz);
  for (TimeNs tp = spline.t_begin_ns(); tp <= spline.t_end_ns(); tp += pose_step)
    gt.push_back({tp, spline.Pose(tp)});
  AAVIO_RETURN_IF_ERROR(sink->WriteImu(*imu));
  AAVIO_RETURN_IF_ERROR(sink->WritePoses(gt));
  report->imu_samples = static_cast<std::int64_t>(imu->size());
  return gt;
}

void WritePreviews(const fs::path& out, const SimulationWorld& world, const EventTally& tally,
                   const std::vector<geometry::StampedPose>& gt) {
  for (int side = 0; side < 2; ++side) {
    cv::imwrite((out / "preview" / (side == 0 ? "events_left.png" : "events_right.png")).string(),
                EventFrame(tally.preview[side], world.rig.width(), world.rig.height()));
  }
  cv::imwrite((out / "preview" / "top_view.png").string(),
              TopView(world.scene, gt, world.T_world_canonical));
}

// The report's rates and the sensor's counts.
void Summarise(const SimulationWorld& world, const StereoEventSimulation& simulation,
               EventTally* tally, SimulationReport* report) {
  report->body_to_camera = world.motion.body_to_camera;
  report->path_smoothing = world.motion.smoothing;
  report->world_effects = world.world_effects.Describe();
  report->duration_s = NsToSeconds(world.spline.t_end_ns() - world.spline.t_begin_ns());
  report->noise_events =
      simulation.generator(0).noise_events() + simulation.generator(1).noise_events();
  report->dropped_events =
      simulation.generator(0).dropped_events() + simulation.generator(1).dropped_events();
  report->sensor = world.sensor.name;
  report->mean_rate_ev_s =
      static_cast<double>(report->events_left) / std::max(report->duration_s, 1e-9);
  std::vector<std::int64_t>& counts = tally->pixel_counts;
  std::sort(counts.begin(), counts.end());
  report->pixel_rate_median_hz =
      static_cast<double>(counts[counts.size() / 2]) / report->duration_s;
  report->pixel_rate_p99_hz =
      static_cast<double>(counts[counts.size() * 99 / 100]) / report->duration_s;
}

}  // namespace

Expected<SimulationReport> Simulate(const SimulationRequest& request,
                                    const std::function<void(double)>& progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (request.out_dir.empty()) return InvalidArgument("an output folder is needed (--out)");
  AAVIO_RETURN_IF_ERROR(request.Validate());
  Expected<SimulationWorld> built = BuildSimulationWorld(request);
  if (!built) return built.status();
  const SimulationWorld& world = *built;
  AAVIO_RETURN_IF_ERROR(PrepareFolder(request, world));

  const fs::path out(request.out_dir);
  Expected<io::SequenceFormat> format = io::ParseSequenceFormat(request.format);
  if (!format) return format.status();
  Expected<std::unique_ptr<io::SequenceWriter>> writer = io::SequenceWriter::Create(
      request.out_dir,
      {.format = *format, .width = world.rig.width(), .height = world.rig.height()});
  if (!writer) return writer.status();
  io::SequenceWriter& sink = **writer;

  SimulationReport report;
  EventTally tally;
  DepthTruthWriter depth(world, out, request.preview);
  StereoEventSimulation simulation(world, request.seed);
  AAVIO_RETURN_IF_ERROR(
      WriteEvents(request, world, &simulation, &sink, &depth, progress, &report, &tally));
  Expected<std::int64_t> depth_maps = depth.Finish();
  if (!depth_maps) return depth_maps.status();
  report.depth_maps = *depth_maps;
  Expected<std::vector<geometry::StampedPose>> gt =
      WriteImuAndPoses(request, world, &sink, &report);
  if (!gt) return gt.status();

  io::SequenceDescription d;
  d.name = fs::absolute(out).lexically_normal().filename().string();
  d.calibration = (out / "calibration").string();
  AAVIO_RETURN_IF_ERROR(sink.Close(&d));
  d.gt_depth = (out / "depth").string();
  if (world.sensor.rig.PerturbsCalibration())
    d.gt_calibration = (out / "calibration_true").string();
  report.sequence_yaml = (out / "sequence.yaml").string();
  AAVIO_RETURN_IF_ERROR(io::WriteSequenceYaml(report.sequence_yaml, d));
  if (request.preview) WritePreviews(out, world, tally, *gt);

  Summarise(world, simulation, &tally, &report);
  report.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return report;
}

}  // namespace aavio::sim
