#pragma once
/// Tracking's stereo check (docs/tracking.md, "Moving objects"): is a map point still what the
/// left camera sees at its pixel? A person walking past a near camera, or a car crossing it,
/// draws fresh ridges on the time surface over the map points it hides and next to those it
/// passes; registered there, the points pull the pose along with the mover. The check asks the
/// current stereo pair, at the predicted pose: the point's left patch (static stereo's 15×7) has
/// events, the right time surface does not match it at the point's disparity (±1 px, cost
/// ½(1 − ZNCC) above 2θ), and does match it elsewhere on the row (cost ≤ θ, more than 2 px
/// away): what the left camera sees there now lies at another depth. Such a point is left out of
/// the tick's registration (not out of the map). A point without events, off the image, whose
/// disparity still matches, or whose patch matches nothing (too little texture to tell) stays.

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "aavio/tracking/registration.hpp"

namespace aavio::tracking {

/// The rectified pair's geometry and static stereo's acceptance, as the check needs them.
struct StereoCheckRig {
  double fb = 0.0;                ///< focal length × baseline [px·m]
  double disparity_offset = 0.0;  ///< cx_left − cx_right: the disparity at infinity [px]
  int min_disparity = 0;          ///< the row search's disparities [px] (the odometry's: 0 to
  int max_disparity = 0;          ///< twice the nearest mapped depth's)
  double zncc_threshold = 0.1;    ///< θ: static stereo accepts a match whose cost is at most θ
};

class StereoCheck {
 public:
  /// `left_ts`, `right_ts`: the tick's rectified time surfaces (CV_8UC1); `valid_mask`: the left
  /// camera's (> 125 usable), all of one size (else every point stays). The images must outlive
  /// the check.
  StereoCheck(const cv::Mat& left_ts, const cv::Mat& right_ts, const cv::Mat& valid_mask,
              const Camera& camera, const StereoCheckRig& rig);

  /// True when the pair shows something at another depth where point `q_cam` (left camera
  /// frame [m]) projects; see the file comment.
  bool SeesSomethingElse(const Eigen::Vector3d& q_cam) const;

 private:
  const cv::Mat& left_;
  const cv::Mat& right_;
  const cv::Mat& valid_mask_;
  Camera camera_;
  StereoCheckRig rig_;
};

}  // namespace aavio::tracking
