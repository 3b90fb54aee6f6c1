#pragma once
/// Zero-mean normalised cross-correlation of image patches, as the cost ½(1 − ZNCC) ∈ [0, 1]
/// (docs/mapping.md). Patches are float images read with row strides.

#include <cmath>
#include <cstddef>
#include <vector>

#include "aavio/common/vector_clones.hpp"

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

/// The rules of ZnccCost that need no more than the right patch's Σb: no correlation if the left
/// patch is flat or, as the reference code does, if the means differ by more than a factor of 5.
inline bool UncorrelatedByMean(const NormalizedPatch& a, double sum) {
  const double mean_b = sum / (a.rows * a.cols);
  return a.norm <= 1e-9 || a.mean > 5.0 * mean_b || mean_b > 5.0 * a.mean;
}

/// ½(1 − ZNCC) from the sums of a right patch (Σb, Σb², Σ(a − ā)b over n pixels); the rules of
/// ZnccCost for flat patches and mean ratios.
inline double ZnccCostFromSums(const NormalizedPatch& a, double sum, double sq, double cross) {
  if (UncorrelatedByMean(a, sum)) return 0.5;
  const double var_b = sq - sum * (sum / (a.rows * a.cols));
  if (var_b <= 1e-9) return 0.5;  // a flat right patch
  return 0.5 * (1.0 - cross / (a.norm * std::sqrt(var_b)));
}

/// ½(1 − ZNCC) of a prepared patch against the patch of `image` at `top_left`; 0.5 (no
/// correlation) when either patch is flat or, as the reference code does, when the patch means
/// differ by more than a factor of 5. Σb is summed first: a patch whose mean already fails the
/// factor-5 test (about a third of temporal stereo's candidates on the twins' AA maps) skips Σb²
/// and the cross term. Each sum keeps its lanes and order, so the cost is the one-pass cost bit
/// for bit.
inline double ZnccCost(const NormalizedPatch& a, const float* top_left, int stride) {
  // Four independent lanes per sum so the compiler can vectorise without reassociating.
  float s4[4] = {0, 0, 0, 0}, q4[4] = {0, 0, 0, 0}, x4[4] = {0, 0, 0, 0};
  float s1 = 0.0f, q1 = 0.0f, x1 = 0.0f;
  for (int r = 0; r < a.rows; ++r) {
    const float* row = top_left + r * stride;
    int c = 0;
    for (; c + 4 <= a.cols; c += 4) {
      for (int j = 0; j < 4; ++j)
        s4[j] += row[c + j];
    }
    for (; c < a.cols; ++c)
      s1 += row[c];
  }
  auto total = [](const float* v4, float v1) {
    return static_cast<double>(v4[0]) + static_cast<double>(v4[1]) + static_cast<double>(v4[2]) +
           static_cast<double>(v4[3]) + static_cast<double>(v1);
  };
  const double sum = total(s4, s1);
  if (UncorrelatedByMean(a, sum)) return 0.5;
  for (int r = 0; r < a.rows; ++r) {
    const float* row = top_left + r * stride;
    const float* pa = a.values + r * a.cols;
    int c = 0;
    for (; c + 4 <= a.cols; c += 4) {
      for (int j = 0; j < 4; ++j) {
        q4[j] += row[c + j] * row[c + j];
        x4[j] += pa[c + j] * row[c + j];
      }
    }
    for (; c < a.cols; ++c) {
      q1 += row[c] * row[c];
      x1 += pa[c] * row[c];
    }
  }
  // Σ (a − ā) b = Σ (a − ā)(b − b̄), so the cross sum needs no mean of b.
  return ZnccCostFromSums(a, sum, total(q4, q1), total(x4, x1));
}

/// ZnccCost of a prepared patch against `count` patches of one image band whose top-left corners
/// are top_left, top_left + 1, …, top_left + count − 1 (a search along a rectified row), into
/// costs[0 … count). The overlapping patches share their column sums, and the cross term is
/// accumulated for all positions at once (for each patch pixel, one multiply-add along the row),
/// so the work per position is ~rows·cols multiply-adds instead of 3·rows·cols. The values equal
/// ZnccCost's up to float rounding in a different summation order. On x86-64 an AVX2 clone is
/// picked at load time where the CPU has it: wider lanes, the same operations per position in the
/// same order (no FMA contraction), so the same costs bit for bit.
AAVIO_AVX2_CLONES inline void ZnccCostsAlongRow(const NormalizedPatch& a, const float* top_left,
                                                int stride, int count, double* costs) {
  if (count <= 0) return;
  const int span = count + a.cols - 1;
  thread_local std::vector<float> col_sum, col_sq, cross, sum, sq;
  col_sum.assign(static_cast<std::size_t>(span), 0.0f);
  col_sq.assign(static_cast<std::size_t>(span), 0.0f);
  cross.assign(static_cast<std::size_t>(count), 0.0f);
  sum.assign(static_cast<std::size_t>(count), 0.0f);
  sq.assign(static_cast<std::size_t>(count), 0.0f);
  float* cs = col_sum.data();
  float* cq = col_sq.data();
  float* x = cross.data();
  for (int r = 0; r < a.rows; ++r) {
    const float* row = top_left + r * stride;
    for (int k = 0; k < span; ++k) {
      cs[k] += row[k];
      cq[k] += row[k] * row[k];
    }
    const float* pa = a.values + r * a.cols;
    for (int c = 0; c < a.cols; ++c) {
      const float ac = pa[c];
      const float* src = row + c;
      for (int j = 0; j < count; ++j)
        x[j] += ac * src[j];
    }
  }
  float* s = sum.data();
  float* q = sq.data();
  for (int c = 0; c < a.cols; ++c) {
    for (int j = 0; j < count; ++j) {
      s[j] += cs[c + j];
      q[j] += cq[c + j];
    }
  }
  for (int j = 0; j < count; ++j) {
    costs[j] = ZnccCostFromSums(a, static_cast<double>(s[j]), static_cast<double>(q[j]),
                                static_cast<double>(x[j]));
  }
}

/// Uniqueness of a cost curve's minimum: true if another local minimum, more than 2 samples from
/// `best`, reaches (1 − uniqueness) of the best's correlation (ZNCC = 1 − 2·cost).
inline bool HasRivalMinimum(const double* costs, int count, int best, double uniqueness) {
  const double best_zncc = 1.0 - 2.0 * costs[best];
  for (int i = 0; i < count; ++i) {
    if (std::abs(i - best) <= 2) continue;
    const bool local_min =
        (i == 0 || costs[i] <= costs[i - 1]) && (i == count - 1 || costs[i] <= costs[i + 1]);
    if (local_min && 1.0 - 2.0 * costs[i] > (1.0 - uniqueness) * best_zncc) return true;
  }
  return false;
}

}  // namespace aavio::mapping
