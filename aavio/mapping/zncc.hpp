#pragma once
/// Zero-mean normalised cross-correlation of image patches, as the cost ½(1 − ZNCC) ∈ [0, 1]
/// (algorithm.md §4.3). Patches are float images read with row strides.

#include <cmath>

namespace aavio::mapping {

/// A patch prepared once for many comparisons: its values minus their mean, and their norm.
struct NormalizedPatch {
  int rows = 0, cols = 0;
  float values[64 * 64];  // rows × cols ≤ 4096
  double norm = 0.0;      // sqrt(Σ (a − ā)²)
  double mean = 0.0;
};

/// Fills `patch` from image rows (stride in floats); false if the patch is larger than 64×64.
inline bool PreparePatch(const float* top_left, int stride, int rows, int cols,
                         NormalizedPatch* patch) {
  if (rows * cols > 64 * 64) return false;
  patch->rows = rows, patch->cols = cols;
  double sum = 0.0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c)
      sum += static_cast<double>(top_left[r * stride + c]);
  }
  patch->mean = sum / (rows * cols);
  double sq = 0.0;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const float a = top_left[r * stride + c] - static_cast<float>(patch->mean);
      patch->values[r * cols + c] = a;
      sq += static_cast<double>(a) * static_cast<double>(a);
    }
  }
  patch->norm = std::sqrt(sq);
  return true;
}

/// ½(1 − ZNCC) of a prepared patch against the patch of `image` at `top_left`; 0.5 (no
/// correlation) when either patch is flat or, as the reference code does, when the patch means
/// differ by more than a factor of 5.
inline double ZnccCost(const NormalizedPatch& a, const float* top_left, int stride) {
  // Four independent lanes per sum so the compiler can vectorise without reassociating.
  float s4[4] = {0, 0, 0, 0}, q4[4] = {0, 0, 0, 0}, x4[4] = {0, 0, 0, 0};
  float s1 = 0.0f, q1 = 0.0f, x1 = 0.0f;
  for (int r = 0; r < a.rows; ++r) {
    const float* row = top_left + r * stride;
    const float* pa = a.values + r * a.cols;
    int c = 0;
    for (; c + 4 <= a.cols; c += 4) {
      for (int j = 0; j < 4; ++j) {
        s4[j] += row[c + j];
        q4[j] += row[c + j] * row[c + j];
        x4[j] += pa[c + j] * row[c + j];
      }
    }
    for (; c < a.cols; ++c) {
      s1 += row[c];
      q1 += row[c] * row[c];
      x1 += pa[c] * row[c];
    }
  }
  auto total = [](const float* v4, float v1) {
    return static_cast<double>(v4[0]) + static_cast<double>(v4[1]) + static_cast<double>(v4[2]) +
           static_cast<double>(v4[3]) + static_cast<double>(v1);
  };
  const double sum = total(s4, s1), sq = total(q4, q1), cross = total(x4, x1);
  const double n = a.rows * a.cols;
  const double mean_b = sum / n;
  const double var_b = sq - sum * mean_b;
  if (a.norm <= 1e-9 || var_b <= 1e-9) return 0.5;
  if (a.mean > 5.0 * mean_b || mean_b > 5.0 * a.mean) return 0.5;
  const double zncc = cross / (a.norm * std::sqrt(var_b));  // Σ (a − ā) b = Σ (a − ā)(b − b̄)
  return 0.5 * (1.0 - zncc);
}

}  // namespace aavio::mapping
