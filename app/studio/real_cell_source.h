#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "app/studio/cell_source.h"
#include "devices/cell/arm_calibration.h"
#include "devices/cell/guided_calibration.h"
#include "devices/cell/real_cell.h"

namespace recon::studio {

/// The studio's real cell (recon-studio --cell PROFILE): the devices a cell profile names, opened
/// once for the studio's life (cell::RealCell), and what the studio shows and drives of them:
/// the live camera with the beacons and the grip drawn where the located camera sees them, the
/// devices' live status, the teleop as joint velocities for the real arm (resolved rate over the
/// UR5 kinematics, then the safety envelope), and the e-stop on the guarded arm.
class RealCellSource final : public CellSource {
 public:
  /// Reads the profile and opens its devices; UserError naming the file, field or device.
  explicit RealCellSource(const std::string& profile_path);

  cell::RealCell& cell() { return *cell_; }

  std::string Kind() const override { return "real"; }
  double DefaultBeaconNoise(const std::string&) const override { return 0.0; }
  double DefaultDemoNoise(const std::string&) const override { return 0.0; }
  /// The tabletop task over the devices, not calibrated yet.
  std::unique_ptr<worlds::World> MakeNewWorld(const teach::SessionSetup& setup) override;
  /// Cell "real" and its devices.
  void DescribeInto(store::SessionManifest& manifest) const override;
  /// The task over the devices with the session's UWB -> table transform, once it has one (a
  /// session taught in the simulated cell, here for trials, has none of this cell).
  std::unique_ptr<worlds::World> MakeSessionWorld(const store::Session& session) override;

  bool HasScriptedTeacher() const override { return false; }
  /// Through the located camera, or along the table's axes (right +x, up +y) when the camera
  /// has no pose.
  Eigen::Vector3d TeleopVelocity(worlds::World& world, const ui::TeleopInput& input, ViewSize view,
                                 const worlds::OrbitCamera& teacher_view,
                                 double speed_m_s) const override;
  std::string PlaySource() const override { return "person-play"; }

  std::optional<std::vector<float>> IdleBeaconReading(worlds::World& world,
                                                      const store::Session& session) override;
  /// The newest camera frame (always: reading it costs nothing), the task's objects (not
  /// located: the list assigns them) and the beacons, drawn where the camera sees them once the
  /// reading is in the table frame.
  bool ShowLive(worlds::World& world, const store::Session& session,
                const std::vector<float>& reading, bool wanted, ViewSize view,
                ui::StudioSnapshot& s) override;
  /// No 3-D view of a real cell yet (it needs a model of where the objects are).
  bool ShowTeacherView(worlds::World&, const worlds::OrbitCamera&, ViewSize,
                       ui::StudioSnapshot&) override {
    return false;
  }
  void ShowArm(const worlds::World& world, ui::StudioSnapshot& s) const override;
  /// Replaces the snapshot's camera, beacon and arm rows by the devices' live status.
  void ShowDevices(ui::StudioSnapshot& s) const override;
  /// The profile's UR5 behind its guard, session or not; null when the profile names no robot.
  safety::GuardedArm* GuardedArmOf(worlds::World*) const override { return cell_->arm(); }

  /// Paced by the teacher who moves the beacon, or, when the profile puts the beacon on the arm
  /// (beacon_on_arm), by the arm carrying it (real_cell_calibration.cc).
  bool GuidesCalibration() const override { return true; }
  /// UserError when the camera's pose in the table frame is unknown (its tags were not seen),
  /// or for a calibration by the arm when the robot is not open.
  void StartGuidedCalibration(int points) override;
  std::optional<calib::CalibrationReport> StepGuidedCalibration(
      ui::GuidedCalibrationView& view) override;
  /// Ends either calibration; a calibration by the arm stops the arm.
  void StopGuidedCalibration() override;
  bool RunsTrials() const override { return cell_->arm() != nullptr; }
  /// Through the located camera; none without its pose.
  std::optional<std::array<float, 2>> TablePixel(const Eigen::Vector3d& p) const override;

 private:
  std::unique_ptr<worlds::World> MakeWorld(const store::SessionManifest& manifest,
                                           const std::string& calibration_path);
  /// The arm's state; none without an arm or while it is gone.
  std::optional<devices::JointState> ArmState() const;
  std::optional<Eigen::Vector3d> GripPoint() const;
  /// One pass of the calibration by the arm: reads the arm and the beacons, commands the arm.
  std::optional<calib::CalibrationReport> StepArmCalibration(ui::GuidedCalibrationView& view);
  void ShowCalibration(const cell::GuidedCalibrationStatus& status,
                       const std::vector<cell::CollectedPose>& poses,
                       ui::GuidedCalibrationView& view) const;

  std::unique_ptr<cell::RealCell> cell_;
  std::unique_ptr<cell::GuidedCalibration> guided_;
  std::unique_ptr<cell::ArmCalibration> arm_calibration_;
  double last_calibration_step_s_ = 0;
  int64_t guided_frame_ = -1;  // the last frame the calibration looked at
  int64_t shown_frame_ = -1;   // the last frame ShowLive showed
};

}  // namespace recon::studio
