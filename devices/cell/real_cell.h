#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "devices/camera/camera_pose.h"
#include "devices/cell/cell_profile.h"
#include "devices/cell/real_cell_world.h"
#include "devices/tags/pinhole_camera.h"
#include "engine/devices/beacon_source.h"
#include "engine/devices/camera.h"
#include "engine/devices/clock.h"
#include "engine/safety/guarded_arm.h"
#include "engine/safety/safety_envelope.h"

namespace recon::uwb {
class BeaconHub;
}
namespace recon::robot {
class UrArm;
}
namespace recon::safety {
class ArmWatchdog;
}

namespace recon::cell {

/// Captures a camera on its own thread and keeps only the newest frame, so readers never wait
/// for the camera and never see a backlog. A failing Capture (an unplugged camera, a corrupt
/// file) is recorded, Latest() throws it until a frame arrives again, and capture is retried
/// every retry_period_s. Stops and joins in the destructor.
class FrameGrabber final : public LatestFrameSource {
 public:
  struct Options {
    /// Frames are taken at most this often: a live camera paces itself, but an image sequence
    /// or a video file would otherwise be read as fast as the disk allows.
    double max_rate_hz = 30.0;
    double retry_period_s = 0.5;
  };

  /// `name` is what errors call the camera, e.g. "/dev/video0". Starts capturing at once.
  FrameGrabber(std::unique_ptr<devices::Camera> camera, std::string name, Options options);
  ~FrameGrabber() override;
  FrameGrabber(const FrameGrabber&) = delete;
  FrameGrabber& operator=(const FrameGrabber&) = delete;

  std::shared_ptr<const devices::CameraFrame> Latest() const override;
  std::string Describe() const override;

  /// Waits up to `timeout_s` for a frame newer than sequence `after` (-1: any frame); nullptr
  /// when none came (see error()).
  std::shared_ptr<const devices::CameraFrame> WaitForFrame(int64_t after, double timeout_s) const;
  /// Why the last Capture failed; empty when it succeeded.
  std::string error() const;
  int64_t frames_captured() const { return frames_captured_; }
  int64_t capture_errors() const { return capture_errors_; }

 private:
  void Run();

  std::unique_ptr<devices::Camera> camera_;  // used by the thread only, after construction
  std::string name_;
  std::string description_;
  Options options_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::shared_ptr<const devices::CameraFrame> latest_;
  std::string error_;
  bool stop_ = false;
  std::atomic<int64_t> frames_captured_{0};
  std::atomic<int64_t> capture_errors_{0};
  std::thread thread_;
};

/// One device of a cell as a status display shows it (the studio's Cell step, `recon cell`).
struct CellDeviceStatus {
  std::string role;    ///< "camera", "beacons" or "arm"
  std::string kind;    ///< e.g. "image sequence", "DWM1001 (tlv)", "UR5 (RTDE + URScript)"
  std::string detail;  ///< the device path, serial port or host
  bool connected = false;
  std::string last_error;  ///< why it is not connected; empty when it is
};

/// How a RealCell opens its devices.
struct RealCellOptions {
  /// The envelope for the arm; base_in_table is replaced by the profile's robot_base_in_table.
  safety::SafetyLimits limits;
  FrameGrabber::Options camera;
  /// How long to wait for the first frame, which the camera pose is estimated from.
  double first_frame_timeout_s = 3.0;
  /// To connect to the robot and for its first state (robot::UrArm::Options::timeout_s).
  double robot_timeout_s = 2.0;
  /// Beacons are read on a thread every this often, so TLV requests go out on time and
  /// readings are taken as they arrive whoever asks for them and when.
  int beacon_poll_ms = 10;
};

/// A real teaching cell opened from its profile: the camera captured on a thread (FrameGrabber;
/// undistorted when calibrated), the DWM1001 beacons behind a uwb::BeaconHub read on a thread,
/// and if the profile names a robot, a robot::UrArm behind safety::GuardedArm with an
/// safety::ArmWatchdog running, on one devices::SteadyClock. The camera's pose in the table frame
/// is estimated once at open from the table tags; when that fails the cell still opens and
/// camera_pose_error() says why. Destruction stops the arm and joins every thread.
class RealCell {
 public:
  /// Opens every device. UserError naming the device (the camera path, the robot host) when
  /// the camera or the robot cannot be opened or the calibration file is bad. A beacon port that
  /// is missing is not an error: the hub retries it, and Status() shows it.
  explicit RealCell(CellProfile profile, const RealCellOptions& options = {});
  ~RealCell();
  RealCell(const RealCell&) = delete;
  RealCell& operator=(const RealCell&) = delete;

  const CellProfile& profile() const { return profile_; }

  /// The newest camera frame (its sequence number inside), nullptr before the first; never
  /// waits. UserError naming the camera while capture is failing.
  std::shared_ptr<const devices::CameraFrame> LatestFrame() const { return grabber_->Latest(); }
  const FrameGrabber& camera() const { return *grabber_; }
  /// The beacons; Poll returns the position readings that arrived since the last call, stamped
  /// on clock(). Thread-safe.
  devices::BeaconSource& beacons();
  /// The guarded arm; null when the profile names no robot.
  safety::GuardedArm* arm() { return guarded_arm_.get(); }
  const devices::Clock& clock() const { return clock_; }
  /// The undistorted image's pinhole model; none without a camera calibration.
  const std::optional<tags::CameraIntrinsics>& intrinsics() const { return intrinsics_; }
  /// Where the camera is in the table frame; none without calibration or when the table tags
  /// were not seen at open (then camera_pose_error() says why).
  const std::optional<camera::CameraPoseEstimate>& camera_pose() const { return camera_pose_; }
  const std::string& camera_pose_error() const { return camera_pose_error_; }

  /// One row per device: the camera, each beacon port, the arm (if any). Thread-safe.
  std::vector<CellDeviceStatus> Status() const;

 private:
  class Beacons;

  void OpenCamera(const RealCellOptions& options);
  /// The digital twin's camera (a profile camera "twin:<layout>"), following the profile's robot.
  std::unique_ptr<devices::Camera> OpenTwinCamera(const std::string& layout) const;
  void EstimatePose(double timeout_s);
  void OpenRobot(const RealCellOptions& options);

  CellProfile profile_;
  devices::SteadyClock clock_;
  std::optional<tags::CameraIntrinsics> intrinsics_;
  std::optional<camera::CameraPoseEstimate> camera_pose_;
  std::string camera_pose_error_;
  std::string camera_kind_;
  std::unique_ptr<FrameGrabber> grabber_;
  std::unique_ptr<Beacons> beacons_;
  std::unique_ptr<robot::UrArm> ur_arm_;
  std::unique_ptr<safety::GuardedArm> guarded_arm_;
  std::unique_ptr<safety::ArmWatchdog> watchdog_;
};

/// The tabletop task over `cell`'s devices (which must outlive the world), with the device
/// names of the profile in its errors (e.g. "UR5 at 192.168.1.10"). UserError when the cell has
/// no robot.
std::unique_ptr<RealCellWorld> MakeRealCellWorld(RealCell& cell, RealCellWorldOptions options);

}  // namespace recon::cell
