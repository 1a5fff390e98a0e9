#pragma once

#include <Eigen/Core>
#include <map>
#include <vector>

#include "devices/tags/pinhole_camera.h"
#include "devices/tags/tag_detector.h"

namespace recon::tags {

/// What is known about a tag before it is seen.
struct TagSpec {
  /// Side of the black border's outer edge (8 of tag36h11's 10 cells), metres.
  double size_m = 0.06;
  /// Table-frame height of the tag's printed face (0 for a tag painted on the table top).
  double height_m = 0.0;
};

/// How a detection becomes a table-frame position.
enum class LocateMethod {
  /// Intersect the ray through the tag centre pixel with the plane z = TagSpec::height_m. Uses
  /// the known height and not the size. The default: on the tags tests' synthetic cell (camera
  /// 1 m up, 5-6 cm tags, noise) it errs by 0.17 mm RMS against kPoseEstimate's 3.2 mm (see
  /// table_locator_test.cc).
  kRayPlane,
  /// libapriltag's estimate_tag_pose from the four corners and TagSpec::size_m, then the
  /// camera-frame translation moved to the table frame. Needs no height, so it also works for a
  /// tag at an unknown height, but its depth comes from the tag's apparent size, which a pixel
  /// of corner error changes by a few percent on a small tag.
  kPoseEstimate,
};

/// A tag located in the table frame.
struct TagLocation {
  int id = -1;
  /// The position the locator's method gives (the tag centre, on its face), metres.
  Eigen::Vector3d position_table_m;
  /// Both methods' answers, so a caller can compare them or choose.
  Eigen::Vector3d ray_plane_table_m;
  Eigen::Vector3d pose_estimate_table_m;
  /// The quality figure: distance between the two methods' answers, metres. They rest on
  /// different knowledge (height vs size), so they agree to within a few millimetres only when
  /// the camera model, the tag size and the tag height are all right; a tag that is tilted, at
  /// the wrong height, of the wrong size, or badly detected shows up here.
  double disagreement_m = 0.0;
  /// estimate_tag_pose's object-space error (squared metres, summed over corners).
  double pose_error = 0.0;
  /// Copied from the detection.
  int hamming = 0;
  double decision_margin = 0.0;
};

/// Turns tag detections from a fixed, calibrated camera into table-frame positions.
class TableLocator {
 public:
  /// Every tag is assumed to match `default_spec` unless SetTagSpec says otherwise. Throws
  /// UserError for a non-positive tag size.
  TableLocator(PinholeCamera camera, TagSpec default_spec,
               LocateMethod method = LocateMethod::kRayPlane);

  /// Declares the size and height of one tag id (e.g. beacon tops differ from table corners).
  void SetTagSpec(int id, TagSpec spec);
  const TagSpec& SpecFor(int id) const;

  /// One location per detection, in the same order. Throws UserError if a tag's plane cannot be
  /// reached from the camera (parallel or behind it), which means the camera pose is wrong.
  std::vector<TagLocation> Locate(const std::vector<TagDetection>& detections) const;
  TagLocation Locate(const TagDetection& detection) const;

  const PinholeCamera& camera() const { return camera_; }
  LocateMethod method() const { return method_; }

 private:
  Eigen::Vector3d PoseEstimate(const TagDetection& detection, double size_m,
                               double* pose_error) const;

  PinholeCamera camera_;
  TagSpec default_spec_;
  LocateMethod method_;
  std::map<int, TagSpec> specs_;
};

}  // namespace recon::tags
