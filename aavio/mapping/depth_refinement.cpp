#include "aavio/mapping/depth_refinement.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "aavio/common/vector_clones.hpp"
#include "aavio/mapping/static_stereo.hpp"

namespace aavio::mapping {

AAVIO_AVX2_CLONES double StudentTScale2(std::span<const float> residuals, double nu,
                                        double s2_start) {
  // r² of the non-zero residuals once, in float (4 partial sums for speed; the values are far
  // from float's precision limits).
  float r2[64 * 64];
  std::size_t n = 0;
  for (const float r : residuals) {
    if (r != 0.0f && n < 64 * 64) r2[n++] = r * r;
  }
  if (n == 0) return s2_start;
  const float nu_f = static_cast<float>(nu), nu1 = static_cast<float>(nu + 1.0);
  double s2 = s2_start;
  for (int iteration = 0; iteration < 20; ++iteration) {
    const float inv_s2 = static_cast<float>(1.0 / s2);
    float sums[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    std::size_t k = 0;
    for (; k + 4 <= n; k += 4) {
      for (int j = 0; j < 4; ++j)
        sums[j] += r2[k + j] / (nu_f + r2[k + j] * inv_s2);
    }
    for (; k < n; ++k)
      sums[0] += r2[k] / (nu_f + r2[k] * inv_s2);
    const double sum =
        static_cast<double>(nu1) * (static_cast<double>(sums[0]) + static_cast<double>(sums[1]) +
                                    static_cast<double>(sums[2]) + static_cast<double>(sums[3]));
    if (sum <= 0.0) return s2_start;
    const double next = sum / static_cast<double>(n);
    const bool converged = std::abs(next - s2) < 0.05 * s2;
    s2 = next;
    if (converged) break;
  }
  return s2;
}

namespace {

constexpr int kMaxPatch = kPatchWidth * kPatchHeight;
constexpr int kMaxIterations = 10;  // LM steps ([ICRA code], [ESVO])

// Bilinear samples of a w×h patch centred at (x, y), one set of weights for all; false if any
// sample would fall outside the image.
AAVIO_AVX2_CLONES bool SamplePatch(const cv::Mat& image, double x, double y, int pw, int ph,
                                   float* out) {
  const double left = x - pw / 2, top = y - ph / 2;
  const int x0 = static_cast<int>(std::floor(left)), y0 = static_cast<int>(std::floor(top));
  if (x0 < 0 || y0 < 0 || x0 + pw >= image.cols || y0 + ph >= image.rows) return false;
  const float fx = static_cast<float>(left - x0), fy = static_cast<float>(top - y0);
  const float w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
  for (int r = 0; r < ph; ++r) {
    const float* a = image.ptr<float>(y0 + r) + x0;
    const float* b = image.ptr<float>(y0 + r + 1) + x0;
    for (int c = 0; c < pw; ++c)
      out[r * pw + c] = w00 * a[c] + w10 * a[c + 1] + w01 * b[c] + w11 * b[c + 1];
  }
  return true;
}

// The residual patch r(ρ) of one match: fixed reference patch minus the patch at ρ's position.
class Residual {
 public:
  Residual(const RefinementInput& in, const Match& m, const RectifiedStereo& stereo, int pw, int ph)
      : in_(in), m_(m), stereo_(stereo), u_(m.u), v_(m.v), pw_(pw), ph_(ph), n_(pw * ph) {
    const cv::Mat& reference = m.kind == StereoKind::kStatic ? in.left_ts : *in.aa_now;
    ok_ = SamplePatch(reference, u_, v_, pw, ph, reference_);
  }
  bool ok() const { return ok_; }
  int size() const { return n_; }
  // r = reference − target at ρ; out-of-image targets give 255 everywhere (then robustified).
  void operator()(double rho, float* r) const {
    float target[kMaxPatch];
    bool inside = false;
    if (m_.kind == StereoKind::kStatic) {
      inside = SamplePatch(in_.right_ts, u_ - stereo_.Disparity(rho), v_, pw_, ph_, target);
    } else {
      double u, v;
      inside = stereo_.Project(in_.T_past_now * stereo_.Backproject(u_, v_, rho), &u, &v) &&
               SamplePatch(*in_.aa_past, u, v, pw_, ph_, target);
    }
    for (int k = 0; k < n_; ++k)
      r[k] = inside ? reference_[k] - target[k] : 255.0f;
  }

 private:
  const RefinementInput& in_;
  const Match& m_;
  const RectifiedStereo& stereo_;
  double u_, v_;
  int pw_, ph_, n_;
  bool ok_ = false;
  float reference_[kMaxPatch];
};

struct Evaluation {
  float weighted[kMaxPatch];      // √w r
  float sqrt_weights[kMaxPatch];  // √w
  double cost = 0.0;              // Σ w r²
};

// Student-t weights of residuals `raw` with the scale s2 (fixed within an LM iteration); the
// weights in float (they only steer the step), the cost summed in double.
AAVIO_AVX2_CLONES void Weigh(const float* raw, int n, double nu, double s2, Evaluation* e) {
  const float nu1 = static_cast<float>(nu + 1.0), nu_f = static_cast<float>(nu),
              inv_s2 = static_cast<float>(1.0 / s2);
  // Element-wise first (vectorised), then the double sum in order.
  float wr2[kMaxPatch];
  for (int k = 0; k < n; ++k) {
    const float rk = raw[k];
    const float w = nu1 / (nu_f + rk * rk * inv_s2);
    const float sw = std::sqrt(w);
    e->sqrt_weights[k] = sw;
    e->weighted[k] = sw * rk;
    wr2[k] = w * rk * rk;
  }
  double cost = 0.0;
  for (int k = 0; k < n; ++k)
    cost += static_cast<double>(wr2[k]);
  e->cost = cost;
}

void Evaluate(const Residual& f, double rho, double nu, double s2, Evaluation* e, float* raw) {
  f(rho, raw);
  Weigh(raw, f.size(), nu, s2, e);
}

// d(√w r)/dρ by a forward difference with the weights of ρ held fixed.
double JacobianNorm2(const Residual& f, double rho, double h, const Evaluation& at, double* jtr) {
  float r[kMaxPatch];
  f(rho + h, r);
  double jtj = 0.0;
  *jtr = 0.0;
  double jtr_h = 0.0;  // Σ (h·j) base, divided by h once at the end
  for (int k = 0; k < f.size(); ++k) {
    const float base = at.weighted[k];
    const float dj = at.sqrt_weights[k] * r[k] - base;  // h·j
    jtj += static_cast<double>(dj * dj);
    jtr_h += static_cast<double>(dj * base);
  }
  *jtr = jtr_h / h;
  return jtj / (h * h);
}

// Minimises the Student-t cost of ρ from `rho` by Levenberg–Marquardt, re-estimating the robust
// scale after each accepted step (IRLS). Returns ρ; `*e` points at its evaluation (one of
// `buffers`) and `*s2` is its scale.
double MinimiseCost(const Residual& f, double rho, double nu, double s2_t, Evaluation (&buffers)[2],
                    const Evaluation** e, double* s2) {
  float raw[kMaxPatch];
  const std::size_t n = static_cast<std::size_t>(f.size());
  // The robust scale from the residuals at ρ (IRLS), then weights with that scale.
  f(rho, raw);
  *s2 = StudentTScale2(std::span<const float>(raw, n), nu, s2_t);
  int current = 0;  // the current evaluation and a trial, swapped on success
  Evaluation* e_ptr = &buffers[0];
  Weigh(raw, f.size(), nu, *s2, e_ptr);
  double jtj = 0.0, jtr = 0.0;
  double lambda = 1e-3;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const double h = std::max(1e-7, 1e-3 * rho);
    jtj = JacobianNorm2(f, rho, h, *e_ptr, &jtr);
    if (jtj <= 1e-12) break;
    bool improved = false;
    double step = 0.0;
    for (int attempt = 0; attempt < 5 && !improved; ++attempt) {
      step = -jtr / (jtj * (1.0 + lambda));
      const double candidate = rho + step;
      if (candidate > 0.0) {
        Evaluation& trial = buffers[1 - current];
        Evaluate(f, candidate, nu, *s2, &trial, raw);
        if (trial.cost < e_ptr->cost) {
          rho = candidate;
          current = 1 - current;
          e_ptr = &buffers[current];
          lambda = std::max(1e-7, lambda * 0.1);
          improved = true;
          continue;
        }
      }
      lambda *= 10.0;
    }
    if (!improved || std::abs(step) < 1e-3 * rho) break;
    // Re-estimate the scale where we are now (IRLS) and re-weigh; the accepted trial left r(ρ)
    // in raw.
    *s2 = StudentTScale2(std::span<const float>(raw, n), nu, s2_t);
    Weigh(raw, f.size(), nu, *s2, e_ptr);
  }
  *e = e_ptr;
  return rho;
}

// The culling (docs/mapping.md): by σ_ρ, by σ_ρ / ρ, by the cost and by the depth range. Temporal
// residuals are on the AA maps, which may have their own thresholds.
bool Kept(const Match& m, const DepthRefinementConfig& c, const TemporalCulls& t,
          InvDepthRange range, double rho, double variance, double cost) {
  const bool temporal = m.kind == StereoKind::kTemporal;
  const double max_stddev =
      temporal && t.max_inv_depth_stddev > 0.0 ? t.max_inv_depth_stddev : c.max_inv_depth_stddev;
  const double residual =
      temporal && t.residual_threshold > 0.0 ? t.residual_threshold : c.residual_threshold;
  const double area = static_cast<double>(kPatchWidth) * kPatchHeight;
  const double sigma = std::sqrt(variance);
  if (sigma > max_stddev) return false;
  if (c.max_relative_stddev > 0.0 && sigma > c.max_relative_stddev * rho) return false;
  if (cost > residual * residual * area) return false;
  return range.Contains(rho);
}

bool RefineOne(const RefinementInput& in, const Match& m, const RectifiedStereo& stereo,
               const DepthRefinementConfig& c, const TemporalCulls& t, InvDepthRange range,
               DepthPoint* out) {
  const Residual f(in, m, stereo, kPatchWidth, kPatchHeight);
  if (!f.ok()) return false;
  const double nu = c.student_t_nu, s2_t = c.student_t_scale * c.student_t_scale;
  Evaluation buffers[2];
  const Evaluation* e = nullptr;
  double s2 = 0.0;
  const double rho = MinimiseCost(f, m.rho, nu, s2_t, buffers, &e, &s2);
  double jtr = 0.0;
  const double jtj = JacobianNorm2(f, rho, std::max(1e-7, 1e-3 * rho), *e, &jtr);
  if (!(rho > 0.001) || jtj <= 0.0) return false;
  const double sigma_t2 = nu / (nu - 2.0) * s2_t;
  const double variance = sigma_t2 / jtj;
  if (!Kept(m, c, t, range, rho, variance, e->cost)) return false;
  out->u = m.u;
  out->v = m.v;
  out->rho = rho;
  out->nu = nu;
  out->s2 = variance * (nu - 2.0) / nu;
  out->residual = e->cost;
  out->age = 0;
  out->kind = m.kind;
  out->near_horizontal = m.near_horizontal;
  return true;
}

}  // namespace

std::vector<DepthPoint> RefineDepths(const RefinementInput& input, std::span<const Match> matches,
                                     const RectifiedStereo& stereo,
                                     const DepthRefinementConfig& refinement,
                                     TemporalCulls temporal, InvDepthRange range) {
  std::vector<DepthPoint> results(matches.size());
  std::vector<char> ok(matches.size(), 0);
  tbb::parallel_for(std::size_t{0}, matches.size(), [&](std::size_t i) {
    const Match& m = matches[i];
    if (m.kind == StereoKind::kTemporal && (input.aa_now == nullptr || input.aa_past == nullptr))
      return;
    ok[i] = RefineOne(input, m, stereo, refinement, temporal, range, &results[i]) ? 1 : 0;
  });
  std::vector<DepthPoint> points;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    if (ok[i]) points.push_back(results[i]);
  }
  return points;
}

}  // namespace aavio::mapping
