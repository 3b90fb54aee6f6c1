#pragma once
/// Edge samples onto the newest edge (aavio; not in the paper or the reference codes).
///
/// Samples are pixels that fired recently (AA counts, or ESVO's newest events), so many lie on
/// the trail a moving edge leaves behind it in the time surface, up to a few pixels from where
/// the edge is at the observation's time. Their depth is right, but as map points they sit where
/// the edge was, and tracking — which pulls map points into the valley of the negative time
/// surface, the newest edge — reads that as the camera being behind: every new map handed to
/// tracking then loses ~1 ms of motion, a scale drift of 2–10 % on the DSEC twins
/// (docs/results.md). Moving each sample along the gradient into the valley removes it.

#include <opencv2/core/mat.hpp>
#include <vector>

#include "aavio/events/edge_sampler.hpp"

namespace aavio::mapping {

/// For each sample: the negative TS (CV_8UC1) along its gradient direction (grad_u/v, CV_32FC1)
/// in 0.25-px steps within ±max_px; the sample moves to the lowest value, refined by a parabola
/// through its neighbours. Samples on a flat surface (|∇| < 1) stay.
void SnapToNewestEdge(const cv::Mat& negative_ts, const cv::Mat& grad_u, const cv::Mat& grad_v,
                      double max_px, std::vector<events::EdgeSample>* samples);

}  // namespace aavio::mapping
