#include "aavio/geometry/velocity.hpp"

#include <algorithm>

#include "aavio/geometry/rotation.hpp"

namespace aavio::geometry {
namespace {

TimeNs MedianInterval(const std::vector<StampedPose>& poses) {
  if (poses.size() < 2) return 0;
  std::vector<TimeNs> dt;
  dt.reserve(poses.size() - 1);
  for (std::size_t i = 1; i < poses.size(); ++i)
    dt.push_back(poses[i].t_ns - poses[i - 1].t_ns);
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

// segment[i]: the index of the segment pose i belongs to (a new one after every gap).
std::vector<int> Segments(const std::vector<StampedPose>& poses, TimeNs median) {
  std::vector<int> segment(poses.size(), 0);
  const double gap = kGapMedianIntervals * static_cast<double>(median);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const bool split = static_cast<double>(poses[i].t_ns - poses[i - 1].t_ns) > gap;
    segment[i] = segment[i - 1] + (split ? 1 : 0);
  }
  return segment;
}

// Local quadratic fits over poses[a, b) in dt = t_j − t_i (a line with two poses, or when not
// allowed): position p(dt)
// = c0 + v·dt + ½a·dt² in the world, rotation log(R_iᵀ·R_j) = ω·dt + ½α·dt² in the body frame;
// the velocities are the linear coefficients at dt = 0.
StampedVelocity Fit(const std::vector<StampedPose>& poses, std::size_t a, std::size_t b,
                    std::size_t i, bool allow_quadratic) {
  StampedVelocity out;
  out.t_ns = poses[i].t_ns;
  if (b - a < 2) return out;
  const RigidTransform& Ti = poses[i].T_world_body;
  const bool quadratic = allow_quadratic && b - a >= 3;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();   // normal equations of [1, dt, dt²]
  Eigen::Matrix3d Bp = Eigen::Matrix3d::Zero();  // rows: Σ basis·pᵀ
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();   // of [dt, dt²] (through the origin)
  Eigen::Matrix<double, 2, 3> Bw = Eigen::Matrix<double, 2, 3>::Zero();
  for (std::size_t j = a; j < b; ++j) {
    const double dt = 1e-9 * static_cast<double>(poses[j].t_ns - poses[i].t_ns);
    const Eigen::Vector3d basis(1.0, dt, quadratic ? dt * dt : 0.0);
    A += basis * basis.transpose();
    Bp += basis * (poses[j].T_world_body.t - Ti.t).transpose();
    const Eigen::Vector2d rb(dt, quadratic ? dt * dt : 0.0);
    C += rb * rb.transpose();
    Bw += rb * LogSO3(Ti.R.transpose() * poses[j].T_world_body.R).transpose();
  }
  if (!quadratic) {  // two poses: a line, and ω through the origin
    A(2, 2) = 1.0;
    C(1, 1) = 1.0;
  }
  const Eigen::Matrix3d cp = A.ldlt().solve(Bp);
  const Eigen::Matrix<double, 2, 3> cw = C.ldlt().solve(Bw);
  if (!cp.allFinite() || !cw.allFinite()) return out;
  out.v_body_mps = Ti.R.transpose() * cp.row(1).transpose();
  out.w_body_radps = cw.row(0).transpose();
  out.valid = true;
  return out;
}

}  // namespace

std::vector<StampedVelocity> EstimateVelocities(const std::vector<StampedPose>& poses,
                                                TimeNs half_window_ns) {
  std::vector<StampedVelocity> out(poses.size());
  const std::vector<int> segment = Segments(poses, MedianInterval(poses));
  std::size_t lo = 0, hi = 0;  // the window [lo, hi) of pose i
  for (std::size_t i = 0; i < poses.size(); ++i) {
    out[i].t_ns = poses[i].t_ns;
    while (lo < i && (segment[lo] != segment[i] || poses[i].t_ns - poses[lo].t_ns > half_window_ns))
      ++lo;
    hi = std::max(hi, i + 1);
    while (hi < poses.size() && segment[hi] == segment[i] &&
           poses[hi].t_ns - poses[i].t_ns <= half_window_ns)
      ++hi;
    // At least the nearest neighbours of the segment.
    std::size_t a = lo, b = hi;
    if (a == i && a > 0 && segment[a - 1] == segment[i]) --a;
    if (b == i + 1 && b < poses.size() && segment[b] == segment[i]) ++b;
    out[i] = Fit(poses, a, b, i, /*allow_quadratic=*/true);
  }
  return out;
}

StampedVelocity NewestVelocity(const std::vector<StampedPose>& recent, TimeNs window_ns) {
  if (recent.empty()) return {};
  const std::size_t i = recent.size() - 1;
  const TimeNs median = MedianInterval(recent);
  const double gap = kGapMedianIntervals * static_cast<double>(median);
  std::size_t a = i;
  while (a > 0 && recent[i].t_ns - recent[a - 1].t_ns <= window_ns &&
         static_cast<double>(recent[a].t_ns - recent[a - 1].t_ns) <= gap)
    --a;
  if (a == i && i > 0 && static_cast<double>(recent[i].t_ns - recent[i - 1].t_ns) <= gap) --a;
  return Fit(recent, a, i + 1, i, /*allow_quadratic=*/false);
}

Sampled SampleAt(const std::vector<StampedPose>& poses,
                 const std::vector<StampedVelocity>& velocities,
                 const std::vector<TimeNs>& stamps_ns) {
  Sampled s;
  const TimeNs median = MedianInterval(poses);
  const std::vector<int> segment = Segments(poses, median);
  auto extrapolate = [&](std::size_t k, TimeNs t) {
    const double dt = 1e-9 * static_cast<double>(t - poses[k].t_ns);
    const RigidTransform& T = poses[k].T_world_body;
    const StampedVelocity& v = velocities[k];
    RigidTransform out;
    out.R = T.R * ExpSO3(v.w_body_radps * dt);
    out.t = T.t + T.R * v.v_body_mps * dt;
    return out;
  };
  for (const TimeNs t : stamps_ns) {
    const auto after = std::lower_bound(poses.begin(), poses.end(), t,
                                        [](const StampedPose& p, TimeNs x) { return p.t_ns < x; });
    const std::size_t k = static_cast<std::size_t>(after - poses.begin());
    StampedPose pose{t, {}};
    StampedVelocity velocity;
    velocity.t_ns = t;
    if (k < poses.size() && poses[k].t_ns == t) {
      pose.T_world_body = poses[k].T_world_body;
      velocity = velocities[k];
    } else if (k > 0 && k < poses.size() && segment[k - 1] == segment[k]) {
      const double alpha = static_cast<double>(t - poses[k - 1].t_ns) /
                           static_cast<double>(poses[k].t_ns - poses[k - 1].t_ns);
      pose.T_world_body = InterpolatePose(poses[k - 1].T_world_body, poses[k].T_world_body, alpha);
      const StampedVelocity &va = velocities[k - 1], &vb = velocities[k];
      velocity.v_body_mps = (1.0 - alpha) * va.v_body_mps + alpha * vb.v_body_mps;
      velocity.w_body_radps = (1.0 - alpha) * va.w_body_radps + alpha * vb.w_body_radps;
      velocity.valid = va.valid && vb.valid;
    } else {
      // Beyond a segment's end (or start) by at most one median interval.
      const bool before_next = k < poses.size() && poses[k].t_ns - t <= median;
      const bool after_last = k > 0 && t - poses[k - 1].t_ns <= median;
      if (!(before_next || after_last) || median == 0) {
        s.missing.push_back(t);
        continue;
      }
      const std::size_t from = after_last ? k - 1 : k;
      pose.T_world_body = extrapolate(from, t);
      velocity = velocities[from];
    }
    velocity.t_ns = t;
    s.poses.push_back(pose);
    s.velocities.push_back(velocity);
  }
  return s;
}

}  // namespace aavio::geometry
