#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "devices/cell/calibration_collector.h"
#include "devices/cell/guided_calibration.h"
#include "engine/calib/calibration.h"
#include "engine/devices/beacon_source.h"
#include "engine/teach/cartesian_teleop.h"

namespace recon::cell {

/// How a calibration by the arm runs: the beacon rides on the tool, and the arm carries it to
/// places spread over the table at two heights.
struct ArmCalibrationOptions {
  int points = 12;
  /// Whose readings count (devices::BeaconSample::beacon); empty: any beacon's.
  std::string beacon;
  /// Where the beacon's antenna sits from the tool point, in the table frame: the tool keeps its
  /// orientation while the arm moves (the Cartesian teleop holds it), so the offset does not turn.
  Eigen::Vector3d beacon_offset_m = Eigen::Vector3d::Zero();
  /// The places: a grid over this part of the table (the beacon's x, y), at two heights of the
  /// beacon over the table, alternating so the places do not all lie in one plane.
  Eigen::Vector2d min_xy{0.30, -0.30}, max_xy{0.75, 0.30};
  double low_m = 0.10, high_m = 0.22;
  /// The tool moves at most this fast, and proportionally slower over its last centimetres.
  double speed_m_s = 0.10;
  double arrive_tolerance_m = 0.004;
  /// Once there: readings count after settle_s (the arm and the beacon's filter come to rest),
  /// and the place is taken after hold_s with at least min_uwb_samples readings.
  double settle_s = 0.5;
  double hold_s = 1.5;
  int min_uwb_samples = 5;
  /// A place not reached in this long is skipped (out of reach, blocked) and said so.
  double move_timeout_s = 20.0;
  double beacon_silent_s = 2.0;
  calib::CalibrationOptions calibration;
};

/// The Calibrate step on a real cell whose profile puts the beacon on the arm
/// (CellProfile::beacon_on_arm): no teacher moves anything. The arm carries the beacon to each
/// planned place through the Cartesian teleop's resolved rate (engine/teach/cartesian_teleop.h)
/// and holds it there; the beacon's true position is the tool point's forward kinematics plus
/// the offset, averaged over the hold, paired with its UWB readings. After every place (or its
/// skip), Fit gives the rigid fit with residuals and outliers, as the other calibrations do.
/// The caller sends the joint velocities Update returns to the guarded arm.
class ArmCalibration {
 public:
  /// UserError for fewer than 3 points, non-positive times or speeds, or an empty region.
  ArmCalibration(ArmCalibrationOptions options, teach::TeleopArm arm);

  /// One pass: `q_rad` the arm's joints now, `samples` the beacon readings that arrived since
  /// the last call, `now_s` the clock they are stamped with, `period_s` the time to the next
  /// call. `arm_held`: the arm is held (its e-stop): the calibration waits, its clocks paused.
  /// Returns the joint velocities to command until the next call (zero while holding).
  std::array<double, 6> Update(const std::array<double, 6>& q_rad,
                               const std::vector<devices::BeaconSample>& samples, double now_s,
                               double period_s, bool arm_held = false);

  const GuidedCalibrationStatus& status() const { return status_; }
  /// Every place was taken or skipped.
  bool Done() const { return next_ >= static_cast<int>(plan_.size()); }
  const std::vector<CollectedPose>& poses() const { return poses_; }
  /// The beacon positions (table frame) the arm carries it to, in order.
  const std::vector<Eigen::Vector3d>& plan() const { return plan_; }
  int skipped() const { return skipped_; }
  /// The fit over the places taken. UserError when fewer than 3 were (naming how many were
  /// skipped) or the set is degenerate.
  calib::CalibrationReport Fit() const;
  /// Where the beacon is for joints `q_rad` (table frame).
  Eigen::Vector3d BeaconAt(const std::array<double, 6>& q_rad) const;

 private:
  void NextPlace(double now_s);
  void Prompt(double now_s, double to_go_m, bool arm_held);

  ArmCalibrationOptions options_;
  teach::TeleopArm arm_;
  std::vector<Eigen::Vector3d> plan_;
  int next_ = 0;
  bool holding_ = false;
  double phase_start_s_ = 0;  ///< when the move or the hold began (shifted while held)
  bool started_ = false;
  double last_now_s_ = 0;
  std::vector<Eigen::Vector3d> hold_truth_, hold_uwb_;
  std::vector<CollectedPose> poses_;
  int skipped_ = 0;
  std::string last_skip_;
  double last_reading_s_ = 0;
  GuidedCalibrationStatus status_;
};

}  // namespace recon::cell
