#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "devices/tags/table_locator.h"
#include "devices/tags/tag_detector.h"
#include "engine/calib/calibration.h"
#include "engine/core/image.h"
#include "engine/devices/beacon_source.h"
#include "engine/devices/camera.h"
#include "engine/devices/clock.h"

namespace recon::cell {

/// How one calibration pose is measured from devices.
struct PoseCollectOptions {
  int beacon_tag_id = 10;    ///< the AprilTag on top of the beacon
  int frames = 5;            ///< camera frames per pose; the tag positions are averaged
  int max_frames = 30;       ///< frames tried before giving up on seeing the tag
  int uwb_samples = 10;      ///< beacon positions averaged per pose (1 s at 10 Hz)
  double uwb_timeout_s = 5;  ///< how long to wait for them
  std::string beacon;        ///< which beacon (BeaconSample::beacon); empty: any
};

/// What one pose gave, with the evidence behind the averages.
struct CollectedPose {
  calib::CalibrationPoint point;
  int frames_with_tag = 0;
  int frames_tried = 0;
  int uwb_samples = 0;
  /// Spread of the tag positions over the frames (max distance from their mean), metres: a
  /// beacon that moved while it was measured shows up here.
  double tag_spread_m = 0;
};

/// The pose a hold of the beacon gives: where it truly was (where the camera saw its tag, or
/// where the arm held it) and its UWB positions, each averaged, with the truth's spread. Both
/// lists must be non-empty.
CollectedPose PoseFromHold(const std::vector<Eigen::Vector3d>& truth_m,
                           const std::vector<Eigen::Vector3d>& uwb_m);

/// The table-frame position of tag `tag_id` in `frame`, or nullopt when it is not detected.
std::optional<tags::TagLocation> LocateTag(tags::TagDetector& detector,
                                           const tags::TableLocator& locator, const RgbImage& frame,
                                           int tag_id);

/// Measures one static beacon pose as a teacher's calibration does, from any camera and beacon
/// source (the simulated cell's or real ones): the beacon's AprilTag in `options.frames` camera
/// frames, located in the table frame, and `options.uwb_samples` UWB positions of the beacon,
/// each averaged. Beacon samples that arrived before the call are discarded (the beacon was
/// being moved). Throws UserError naming the pose (`pose_label`) when the tag is not seen in
/// `max_frames` frames or the beacon gives too few positions in time.
CollectedPose CollectPose(devices::Camera& camera, devices::BeaconSource& beacons,
                          const tags::TableLocator& locator, const devices::Clock& clock,
                          const PoseCollectOptions& options, const std::string& pose_label);

}  // namespace recon::cell
