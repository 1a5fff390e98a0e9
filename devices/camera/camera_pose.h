#pragma once

#include <vector>

#include "devices/camera/table_tags_file.h"
#include "devices/tags/pinhole_camera.h"
#include "devices/tags/tag_detector.h"

namespace recon::camera {

/// A camera's pose in the table frame as recovered from tags at known places, and how well it
/// explains them.
struct CameraPoseEstimate {
  /// The located camera. A default-constructed estimate (e.g. a member of a result filled in
  /// later) holds a placeholder: unit focal lengths, at the table origin, axes along the table's;
  /// EstimateCameraPose always replaces it.
  tags::PinholeCamera camera{tags::CameraIntrinsics{1.0, 1.0, 0.0, 0.0, 1, 1},
                             Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  /// Over every corner used: distance between the detected corner and the corner projected
  /// through `camera`, pixels. A few tenths of a pixel is a good fit; several pixels mean a
  /// table tag is misplaced or mis-sized in the description, or the intrinsics are wrong.
  double reprojection_rms_px = 0.0;
  double reprojection_max_px = 0.0;
  std::vector<int> used_ids;     ///< table tags seen and used, ascending
  std::vector<int> missing_ids;  ///< table tags not seen
  std::vector<int> unknown_ids;  ///< tags seen that the description does not list (ignored)
};

/// Estimates where a fixed camera is and how it is turned, in the table frame, from detections
/// of tags whose table positions are known (e.g. one taped at each corner of the table). All
/// corners of all known tags go into one cv::solvePnP (SQPnP, then Levenberg-Marquardt
/// refinement), so the pose is as good as the spread of the tags allows. `intrinsics` describe
/// the image the detections came from, which must be undistorted (see Undistorter). The result
/// is what TableLocator needs to place other tags on the table.
///
/// Throws UserError when fewer than `min_tags` of the table tags were seen (listing the ones
/// seen), since one small tag gives a poorly constrained pose.
CameraPoseEstimate EstimateCameraPose(const tags::CameraIntrinsics& intrinsics,
                                      const std::vector<TableTag>& table_tags,
                                      const std::vector<tags::TagDetection>& detections,
                                      int min_tags = 2);

}  // namespace recon::camera
