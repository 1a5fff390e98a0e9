#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "devices/cell/calibration_collector.h"
#include "devices/tags/pinhole_camera.h"
#include "devices/tags/table_locator.h"
#include "devices/tags/tag_detector.h"
#include "engine/calib/calibration.h"
#include "engine/core/image.h"
#include "engine/devices/beacon_source.h"

namespace recon::cell {

/// How a teacher-paced calibration decides that a pose is taken.
struct GuidedCalibrationOptions {
  int points = 8;
  /// Whose readings count (devices::BeaconSample::beacon); empty: any beacon's.
  std::string beacon;
  int beacon_tag_id = 10;
  tags::TagSpec beacon_tag{0.0352, 0.06};
  /// A pose is taken once the tag has held still (within steady_tolerance_m) for steady_s...
  double steady_s = 1.0;
  double steady_tolerance_m = 0.005;
  /// ...and at least this many beacon readings arrived while it held, not counting the first
  /// settle_s, which may still be on their way from where the beacon was.
  int min_uwb_samples = 5;
  double settle_s = 0.2;
  /// A new place is this far from every pose taken (a fit needs the poses spread out).
  double min_separation_m = 0.08;
  /// With no reading for this long, the beacon is called silent (unplugged, flat battery).
  double beacon_silent_s = 2.0;
  /// The camera is looked at this often at most: detecting tags in a 1280 x 960 frame costs
  /// tens of milliseconds of the thread that calls Update.
  double look_period_s = 0.2;
  calib::CalibrationOptions calibration;
};

/// What the teacher sees while a guided calibration runs.
struct GuidedCalibrationStatus {
  int taken = 0, total = 0;
  /// What to do now, in a sentence ("Move the beacon to place 3 of 8 ...").
  std::string prompt;
  bool tag_seen = false;
  Eigen::Vector3d tag_table_m = Eigen::Vector3d::Zero();  ///< valid when tag_seen
  std::array<float, 2> tag_pixel{0, 0};                   ///< the tag's centre in the frame
  std::optional<Eigen::Vector3d> beacon_uwb_m;            ///< the newest reading, UWB frame
  bool beacon_silent = false;
  /// How far through the hold the current place is, 0 to 1.
  double held_fraction = 0;
};

/// The Calibrate step on a real cell, paced by the teacher: the teacher puts the beacon (its
/// AprilTag up) somewhere new on the table and lets go; once the camera has seen the tag hold
/// still and the beacon has reported from there, the place is taken (the tag's table position
/// and the beacon's UWB position, each averaged over the hold) and the teacher is asked for the
/// next one. After `points` places, Fit gives the rigid UWB -> table fit with its residuals and
/// outliers, as the simulated cell's calibration does. A tag out of view, a place too near one
/// taken before and a silent beacon are said in the prompt; none ends the calibration.
class GuidedCalibration {
 public:
  /// `camera` is the located camera (its pose in the table frame) whose undistorted frames
  /// Look is given. UserError for fewer than 3 points or non-positive times.
  GuidedCalibration(const tags::PinholeCamera& camera, GuidedCalibrationOptions options);

  /// One pass: `frame` is the camera's newest frame (null when none; looked at no more often
  /// than look_period_s), `samples` the beacon readings that arrived since the last call, `now_s`
  /// the time on the clock the samples are stamped with.
  void Update(const RgbImage* frame, const std::vector<devices::BeaconSample>& samples,
              double now_s);

  const GuidedCalibrationStatus& status() const { return status_; }
  bool Done() const { return static_cast<int>(poses_.size()) >= options_.points; }
  const std::vector<CollectedPose>& poses() const { return poses_; }
  /// The fit over the places taken. UserError for a degenerate set (calib::Calibrate).
  calib::CalibrationReport Fit() const;

 private:
  void Look(const RgbImage& frame, double now_s);
  void TakePose();
  void Prompt(double now_s);

  GuidedCalibrationOptions options_;
  tags::TableLocator locator_;
  std::unique_ptr<tags::TagDetector> detector_;
  GuidedCalibrationStatus status_;
  std::vector<CollectedPose> poses_;
  // The hold under way: where the tag settled, since when, what was seen and read meanwhile.
  std::optional<Eigen::Vector3d> anchor_;
  double hold_start_s_ = 0;
  std::vector<Eigen::Vector3d> hold_tags_;
  std::vector<Eigen::Vector3d> hold_uwb_;
  int too_near_pose_ = -1;  // the pose the tag sits too near, or -1
  double last_look_s_ = -1e9;
  double last_reading_s_;
  bool looked_ = false;
};

}  // namespace recon::cell
