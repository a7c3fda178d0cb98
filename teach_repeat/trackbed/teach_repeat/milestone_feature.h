// One feature of a teach-map milestone (teach_map.h): where it was in the milestone's
// first and last image, its 3-D point and a patch of its last image.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace trackbed::teach_repeat {

/// One feature of a milestone.
struct MilestoneFeature {
  cv::Point2f first_px;  ///< position in the milestone's first (key) image [px]
  cv::Point2f last_px;   ///< position in its last image, KLT-tracked [px]
  /// 3-D point in the first camera's frame [m] (3D milestones; zero otherwise).
  Eigen::Vector3d p_first = Eigen::Vector3d::Zero();
  /// patch_size_px × patch_size_px CV_8UC1 patch of the last image centred on last_px.
  cv::Mat patch;
};

}  // namespace trackbed::teach_repeat
