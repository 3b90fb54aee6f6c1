#include "aavio/events/rectified_image.hpp"

#include <opencv2/imgproc.hpp>

namespace aavio::events {

ImageRectifier::ImageRectifier(const geometry::RectificationMaps& maps)
    : valid_mask_(maps.valid_mask) {
  cv::convertMaps(maps.remap_x, maps.remap_y, map_xy_, map_frac_, CV_16SC2);
}

void ImageRectifier::Rectify(const cv::Mat& raw, cv::Mat* rectified) const {
  cv::remap(raw, *rectified, map_xy_, map_frac_, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar(0));
}

}  // namespace aavio::events
