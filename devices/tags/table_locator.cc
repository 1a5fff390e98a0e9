#include "devices/tags/table_locator.h"

#include <apriltag/apriltag.h>
#include <apriltag/apriltag_pose.h>

#include <cstdlib>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "engine/core/error.h"

namespace recon::tags {
namespace {

void CheckSpec(int id, const TagSpec& spec) {
  if (!(spec.size_m > 0.0)) {
    throw UserError("tag " + std::to_string(id) + ": size must be positive, got " +
                    std::to_string(spec.size_m) + " m");
  }
}

// matd_* is not exported by Debian's libapriltag, so matrices handed to it are malloc'ed by hand
// (matd_t is a header followed by its elements) and everything it returns is released with free.
struct FreeDeleter {
  void operator()(void* p) const { std::free(p); }
};
using MatdPtr = std::unique_ptr<matd_t, FreeDeleter>;

MatdPtr MakeMatd(int rows, int cols, const double* data) {
  MatdPtr m(static_cast<matd_t*>(std::malloc(sizeof(matd_t) + sizeof(double) * rows * cols)));
  if (!m) throw std::bad_alloc();
  m->nrows = rows;
  m->ncols = cols;
  for (int i = 0; i < rows * cols; ++i) m->data[i] = data[i];
  return m;
}

}  // namespace

TableLocator::TableLocator(PinholeCamera camera, TagSpec default_spec, LocateMethod method)
    : camera_(std::move(camera)), default_spec_(default_spec), method_(method) {
  CheckSpec(-1, default_spec_);
}

void TableLocator::SetTagSpec(int id, TagSpec spec) {
  CheckSpec(id, spec);
  specs_[id] = spec;
}

const TagSpec& TableLocator::SpecFor(int id) const {
  const auto it = specs_.find(id);
  return it == specs_.end() ? default_spec_ : it->second;
}

std::vector<TagLocation> TableLocator::Locate(const std::vector<TagDetection>& detections) const {
  std::vector<TagLocation> locations;
  locations.reserve(detections.size());
  for (const TagDetection& detection : detections) locations.push_back(Locate(detection));
  return locations;
}

TagLocation TableLocator::Locate(const TagDetection& detection) const {
  const TagSpec& spec = SpecFor(detection.id);
  TagLocation location;
  location.id = detection.id;
  location.hamming = detection.hamming;
  location.decision_margin = detection.decision_margin;
  location.ray_plane_table_m = camera_.IntersectHorizontalPlane(detection.center_px, spec.height_m);
  location.pose_estimate_table_m = PoseEstimate(detection, spec.size_m, &location.pose_error);
  location.disagreement_m = (location.ray_plane_table_m - location.pose_estimate_table_m).norm();
  location.position_table_m = method_ == LocateMethod::kRayPlane ? location.ray_plane_table_m
                                                                 : location.pose_estimate_table_m;
  return location;
}

Eigen::Vector3d TableLocator::PoseEstimate(const TagDetection& detection, double size_m,
                                           double* pose_error) const {
  // estimate_tag_pose reads the homography (initial guess) and the corners (refinement) of a
  // libapriltag detection, so one is rebuilt from ours.
  MatdPtr homography = MakeMatd(3, 3, detection.homography.data());
  apriltag_detection_t raw{};
  raw.id = detection.id;
  raw.hamming = detection.hamming;
  raw.decision_margin = static_cast<float>(detection.decision_margin);
  raw.H = homography.get();
  raw.c[0] = detection.center_px.x();
  raw.c[1] = detection.center_px.y();
  for (int k = 0; k < 4; ++k) {
    raw.p[k][0] = detection.corners_px[k].x();
    raw.p[k][1] = detection.corners_px[k].y();
  }
  const CameraIntrinsics& intrinsics = camera_.intrinsics();
  apriltag_detection_info_t info;
  info.det = &raw;
  info.tagsize = size_m;
  info.fx = intrinsics.fx;
  info.fy = intrinsics.fy;
  info.cx = intrinsics.cx;
  info.cy = intrinsics.cy;
  apriltag_pose_t pose{nullptr, nullptr};
  *pose_error = estimate_tag_pose(&info, &pose);
  const MatdPtr rotation(pose.R);
  const MatdPtr translation(pose.t);
  // t is the tag centre in the AprilTag camera frame (z forward, y down): the frame the camera's
  // table_R_cv describes.
  const Eigen::Vector3d tag_cv(translation->data[0], translation->data[1], translation->data[2]);
  return camera_.position_table_m() + camera_.table_R_cv() * tag_cv;
}

}  // namespace recon::tags
