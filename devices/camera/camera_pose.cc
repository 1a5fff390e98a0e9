#include "devices/camera/camera_pose.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/calib3d.hpp>

#include "engine/core/error.h"

namespace recon::camera {

namespace {

std::string IdList(const std::vector<int>& ids) {
  if (ids.empty()) return "none";
  std::string text;
  for (int id : ids) text += (text.empty() ? "" : ", ") + std::to_string(id);
  return text;
}

}  // namespace

CameraPoseEstimate EstimateCameraPose(const tags::CameraIntrinsics& intrinsics,
                                      const std::vector<TableTag>& table_tags,
                                      const std::vector<tags::TagDetection>& detections,
                                      int min_tags) {
  std::map<int, const TableTag*> known;
  for (const TableTag& tag : table_tags) known[tag.id] = &tag;

  std::vector<cv::Point3d> object_points;
  std::vector<cv::Point2d> image_points;
  std::vector<const tags::TagDetection*> used;
  std::vector<int> used_ids, unknown_ids, missing_ids;
  for (const tags::TagDetection& detection : detections) {
    const auto it = known.find(detection.id);
    if (it == known.end()) {
      unknown_ids.push_back(detection.id);
      continue;
    }
    if (std::find(used_ids.begin(), used_ids.end(), detection.id) != used_ids.end()) {
      continue;  // a tag id seen twice: one of the two is not the table's; keep the first
    }
    used_ids.push_back(detection.id);
    used.push_back(&detection);
    const std::vector<Eigen::Vector3d> corners = it->second->Corners();
    for (int k = 0; k < 4; ++k) {
      object_points.emplace_back(corners[k].x(), corners[k].y(), corners[k].z());
      // Detections put pixel centres at +0.5, OpenCV at integers (pinhole_camera.h).
      image_points.emplace_back(detection.corners_px[k].x() - 0.5,
                                detection.corners_px[k].y() - 0.5);
    }
  }
  for (const TableTag& tag : table_tags) {
    if (std::find(used_ids.begin(), used_ids.end(), tag.id) == used_ids.end()) {
      missing_ids.push_back(tag.id);
    }
  }
  std::sort(used_ids.begin(), used_ids.end());
  std::sort(unknown_ids.begin(), unknown_ids.end());
  if (static_cast<int>(used_ids.size()) < std::max(1, min_tags)) {
    throw UserError("cannot find the camera pose: it sees " + std::to_string(used_ids.size()) +
                    " of the " + std::to_string(table_tags.size()) + " table tags (seen: " +
                    IdList(used_ids) + "; not seen: " + IdList(missing_ids) + "), at least " +
                    std::to_string(std::max(1, min_tags)) + " are needed");
  }

  const cv::Matx33d k(intrinsics.fx, 0.0, intrinsics.cx - 0.5,  //
                      0.0, intrinsics.fy, intrinsics.cy - 0.5,  //
                      0.0, 0.0, 1.0);
  cv::Mat rvec, tvec;
  bool ok = false;
  try {
    // SQPnP finds the global optimum for planar and non-planar layouts alike; LM then polishes
    // the reprojection error, which is what the tolerances of TableLocator rest on.
    ok = cv::solvePnP(object_points, image_points, k, cv::noArray(), rvec, tvec, false,
                      cv::SOLVEPNP_SQPNP);
    if (ok) cv::solvePnPRefineLM(object_points, image_points, k, cv::noArray(), rvec, tvec);
  } catch (const cv::Exception& e) {
    throw UserError("cannot find the camera pose from tags " + IdList(used_ids) + ": " + e.err);
  }
  if (!ok) throw UserError("cannot find the camera pose from tags " + IdList(used_ids));

  cv::Matx33d r_cv;
  cv::Rodrigues(rvec, r_cv);
  // solvePnP gives x_cv = R * x_table + t; the camera's axes in the table frame are R's rows.
  Eigen::Matrix3d cv_R_table;
  for (int i = 0; i < 9; ++i) cv_R_table(i / 3, i % 3) = r_cv(i / 3, i % 3);
  const Eigen::Vector3d t(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  const Eigen::Matrix3d table_R_cv = cv_R_table.transpose();
  const Eigen::Vector3d position = -table_R_cv * t;

  CameraPoseEstimate estimate{tags::PinholeCamera(intrinsics, position, table_R_cv),
                              0.0,
                              0.0,
                              used_ids,
                              missing_ids,
                              unknown_ids};
  double sum_sq = 0.0, worst = 0.0;
  for (size_t i = 0; i < used.size(); ++i) {
    const std::vector<Eigen::Vector3d> corners = known.at(used[i]->id)->Corners();
    for (int c = 0; c < 4; ++c) {
      const double e = (estimate.camera.Project(corners[c]) - used[i]->corners_px[c]).norm();
      sum_sq += e * e;
      worst = std::max(worst, e);
    }
  }
  estimate.reprojection_rms_px = std::sqrt(sum_sq / (4.0 * used.size()));
  estimate.reprojection_max_px = worst;
  return estimate;
}

}  // namespace recon::camera
