// RealCellSource's Calibrate step, in one of two ways, whichever the profile says: the teacher
// moves the beacon place by place (cell::GuidedCalibration, the camera locating its tag), or the
// beacon rides on the arm's tool and the arm carries it (cell::ArmCalibration, the arm's
// kinematics locating it). Both fill the same live view and end in the same fit.

#include <memory>
#include <string>
#include <utility>

#include "app/studio/real_cell_source.h"
#include "engine/core/error.h"

namespace recon::studio {

namespace {

// The beacon the task reads (RealCellWorldOptions::plate_beacon).
constexpr char kCalibratedBeacon[] = "plate";

}  // namespace

void RealCellSource::StartGuidedCalibration(int points) {
  if (const std::optional<Eigen::Vector3d>& offset = cell_->profile().beacon_on_arm_offset_m) {
    safety::GuardedArm* arm = cell_->arm();
    if (arm == nullptr)
      throw UserError("cannot calibrate by the arm: the cell's robot is not open");
    cell::ArmCalibrationOptions options;
    options.points = points;
    options.beacon = kCalibratedBeacon;
    options.beacon_offset_m = *offset;
    arm_calibration_ = std::make_unique<cell::ArmCalibration>(
        options, teach::TeleopArmOf(arm->envelope().limits()));
    last_calibration_step_s_ = cell_->clock().NowSeconds();
    return;
  }
  if (!cell_->camera_pose()) {
    throw UserError("cannot calibrate: the camera's pose in the table frame is unknown (" +
                    cell_->camera_pose_error() +
                    "); the camera must see the table's corner tags when the studio opens the "
                    "cell, so clear them and restart the studio");
  }
  const cell::BeaconTagProfile& tag = cell_->profile().beacon_tag;
  cell::GuidedCalibrationOptions options;
  options.points = points;
  options.beacon = kCalibratedBeacon;
  options.beacon_tag_id = tag.id;
  options.beacon_tag = {tag.size_m, tag.height_m};
  guided_ = std::make_unique<cell::GuidedCalibration>(cell_->camera_pose()->camera, options);
  guided_frame_ = -1;
}

void RealCellSource::ShowCalibration(const cell::GuidedCalibrationStatus& status,
                                     const std::vector<cell::CollectedPose>& poses,
                                     ui::GuidedCalibrationView& view) const {
  view.points_taken = status.taken;
  view.points_target = status.total;
  view.prompt = status.prompt;
  view.tag_seen = status.tag_seen;
  view.tag_pixel = status.tag_pixel;
  view.taken_pixel.clear();
  for (const cell::CollectedPose& pose : poses) {
    if (const std::optional<std::array<float, 2>> px = TablePixel(pose.point.tag_m)) {
      view.taken_pixel.push_back(*px);
    }
  }
  view.beacon_uwb_m.clear();
  if (status.beacon_uwb_m) {
    for (int i = 0; i < 3; ++i) {
      view.beacon_uwb_m.push_back(static_cast<float>((*status.beacon_uwb_m)[i]));
    }
  }
  view.beacon_silent = status.beacon_silent;
  view.held_fraction = static_cast<float>(status.held_fraction);
}

std::optional<calib::CalibrationReport> RealCellSource::StepGuidedCalibration(
    ui::GuidedCalibrationView& view) {
  if (arm_calibration_) return StepArmCalibration(view);
  if (!guided_) return std::nullopt;
  std::shared_ptr<const devices::CameraFrame> frame;
  std::string camera_error;
  try {
    frame = cell_->LatestFrame();
  } catch (const UserError& e) {
    camera_error = e.what();  // said in the prompt; the calibration goes on when it is back
  }
  const RgbImage* image = nullptr;
  if (frame && frame->sequence != guided_frame_) {
    guided_frame_ = frame->sequence;
    image = &frame->image;
  }
  guided_->Update(image, cell_->beacons().Poll(), cell_->clock().NowSeconds());
  ShowCalibration(guided_->status(), guided_->poses(), view);
  if (!camera_error.empty()) {
    view.prompt = "The camera is not delivering: " + camera_error;
    view.tag_seen = false;
  }
  if (!guided_->Done()) return std::nullopt;
  const std::unique_ptr<cell::GuidedCalibration> done = std::move(guided_);
  return done->Fit();
}

std::optional<calib::CalibrationReport> RealCellSource::StepArmCalibration(
    ui::GuidedCalibrationView& view) {
  safety::GuardedArm* arm = cell_->arm();
  const double now = cell_->clock().NowSeconds();
  const double period = now - last_calibration_step_s_;
  last_calibration_step_s_ = now;
  // A gone arm throws UserError: the studio stops the calibration and says why.
  const devices::JointState state = arm->State();
  const bool held = arm->emergency_stopped();
  const std::array<double, 6> velocity =
      arm_calibration_->Update(state.position_rad, cell_->beacons().Poll(), now, period, held);
  if (!held) arm->CommandJointVelocities(velocity);
  ShowCalibration(arm_calibration_->status(), arm_calibration_->poses(), view);
  if (!arm_calibration_->Done()) return std::nullopt;
  arm->Stop();
  const std::unique_ptr<cell::ArmCalibration> done = std::move(arm_calibration_);
  return done->Fit();
}

void RealCellSource::StopGuidedCalibration() {
  guided_.reset();
  if (!arm_calibration_) return;
  arm_calibration_.reset();
  try {
    if (safety::GuardedArm* arm = cell_->arm()) arm->Stop();
  } catch (const UserError&) {
    // The arm is gone: its controller stopped it when the commands stopped.
  }
}

}  // namespace recon::studio
