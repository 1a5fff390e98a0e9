#include "devices/cell/real_cell.h"

#include "devices/cell/twin_camera.h"
#include "devices/cell/twin_scene.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <exception>

#include "devices/camera/camera_calibration_file.h"
#include "devices/camera/open_camera.h"
#include "devices/camera/table_tags_file.h"
#include "devices/cell/twin_camera.h"
#include "devices/cell/twin_scene.h"
#include "devices/robot/ur_arm.h"
#include "devices/tags/tag_detector.h"
#include "devices/uwb/beacon_hub.h"
#include "engine/core/error.h"
#include "engine/safety/arm_watchdog.h"

namespace recon::cell {

namespace {

using SteadyTime = std::chrono::steady_clock::time_point;

std::chrono::steady_clock::duration Seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(s));
}

const char* CameraKindName(camera::CameraSourceKind kind) {
  switch (kind) {
    case camera::CameraSourceKind::kV4l2Device:
      return "V4L2 camera";
    case camera::CameraSourceKind::kVideoFile:
      return "video file";
    case camera::CameraSourceKind::kImageSequence:
      return "image sequence";
  }
  return "camera";
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// FrameGrabber

FrameGrabber::FrameGrabber(std::unique_ptr<devices::Camera> camera, std::string name,
                           Options options)
    : camera_(std::move(camera)), name_(std::move(name)), options_(options) {
  if (camera_ == nullptr) throw std::invalid_argument("FrameGrabber: no camera");
  if (!(options_.max_rate_hz > 0) || !(options_.retry_period_s > 0)) {
    throw UserError("camera " + name_ + ": the capture rate and retry period must be positive");
  }
  description_ = camera_->Describe();
  thread_ = std::thread([this] { Run(); });
}

FrameGrabber::~FrameGrabber() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameGrabber::Run() {
  SteadyTime next = std::chrono::steady_clock::now();
  while (true) {
    {
      std::unique_lock lock(mutex_);
      changed_.wait_until(lock, next, [this] { return stop_; });
      if (stop_) return;
    }
    const SteadyTime started = std::chrono::steady_clock::now();
    try {
      auto frame = std::make_shared<const devices::CameraFrame>(camera_->Capture());
      {
        std::lock_guard lock(mutex_);
        latest_ = std::move(frame);
        error_.clear();
      }
      ++frames_captured_;
      next = started + Seconds(1.0 / options_.max_rate_hz);
    } catch (const std::exception& e) {
      // Kept, not fatal: a camera that was unplugged may come back, a bad file may be skipped.
      {
        std::lock_guard lock(mutex_);
        error_ = e.what();
      }
      ++capture_errors_;
      next = std::chrono::steady_clock::now() + Seconds(options_.retry_period_s);
    }
    changed_.notify_all();
  }
}

std::shared_ptr<const devices::CameraFrame> FrameGrabber::Latest() const {
  std::lock_guard lock(mutex_);
  if (!error_.empty()) throw UserError("camera " + name_ + ": " + error_);
  return latest_;
}

std::shared_ptr<const devices::CameraFrame> FrameGrabber::WaitForFrame(int64_t after,
                                                                       double timeout_s) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                    [&] { return stop_ || (latest_ != nullptr && latest_->sequence > after); });
  return latest_ != nullptr && latest_->sequence > after ? latest_ : nullptr;
}

std::string FrameGrabber::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

std::string FrameGrabber::Describe() const { return description_; }

// ---------------------------------------------------------------------------------------------
// RealCell::Beacons

/// The hub read on its own thread (BeaconHub is not thread-safe, and a TLV tag is only asked for
/// a position while someone polls), its readings queued for Poll and restamped on the cell's
/// clock. Status is copied out after every poll, so a status display never waits on the hub
/// (which blocks for up to the answer timeout while it retries an unplugged tag).
class RealCell::Beacons final : public devices::BeaconSource {
 public:
  Beacons(uwb::BeaconHubOptions options, const devices::Clock& clock, int poll_ms)
      : hub_(std::make_unique<uwb::BeaconHub>(std::move(options))),
        clock_(clock),
        poll_ms_(std::max(1, poll_ms)) {
    CopyStatus();
    thread_ = std::thread([this] { Run(); });
  }

  ~Beacons() override {
    stop_ = true;
    thread_.join();
  }

  std::vector<devices::BeaconSample> Poll() override {
    std::lock_guard lock(mutex_);
    std::vector<devices::BeaconSample> out(queue_.begin(), queue_.end());
    queue_.clear();
    return out;
  }
  devices::BeaconSourceStats Stats() const override {
    std::lock_guard lock(mutex_);
    return stats_;
  }
  std::string Describe() const override {
    std::lock_guard lock(mutex_);
    return description_;
  }
  std::vector<uwb::BeaconPortStatus> PortStatus() const {
    std::lock_guard lock(mutex_);
    return ports_;
  }

 private:
  // Nobody may poll for a long while (the teacher setting up); older readings are dropped.
  static constexpr size_t kMaxQueued = 4096;

  void CopyStatus() {
    auto stats = hub_->Stats();
    auto description = hub_->Describe();
    auto ports = hub_->Status();
    std::lock_guard lock(mutex_);
    stats_ = stats;
    description_ = std::move(description);
    ports_ = std::move(ports);
  }

  void Run() {
    while (!stop_) {
      std::vector<devices::BeaconSample> samples = hub_->Poll();
      const double now_s = clock_.NowSeconds();
      for (devices::BeaconSample& s : samples) s.timestamp_s = now_s;
      CopyStatus();
      {
        std::lock_guard lock(mutex_);
        queue_.insert(queue_.end(), samples.begin(), samples.end());
        while (queue_.size() > kMaxQueued) queue_.pop_front();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(poll_ms_));
    }
  }

  std::unique_ptr<uwb::BeaconHub> hub_;  // the thread's alone once it runs
  const devices::Clock& clock_;
  int poll_ms_;
  mutable std::mutex mutex_;  // guards the copies and the queue below
  devices::BeaconSourceStats stats_;
  std::string description_;
  std::vector<uwb::BeaconPortStatus> ports_;
  std::deque<devices::BeaconSample> queue_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// ---------------------------------------------------------------------------------------------
// RealCell

RealCell::RealCell(CellProfile profile, const RealCellOptions& options)
    : profile_(std::move(profile)) {
  OpenCamera(options);
  uwb::BeaconHubOptions hub;
  hub.ports = profile_.beacons.ports;
  hub.names = profile_.beacons.names;
  hub.driver.mode = profile_.beacons.mode;
  try {
    beacons_ = std::make_unique<Beacons>(hub, clock_, options.beacon_poll_ms);
  } catch (const UserError& e) {
    throw UserError("beacons (" + profile_.path + "): " + e.what());
  }
  if (profile_.robot) OpenRobot(options);
  // Last: the frame the pose comes from has had every other device's opening time to arrive.
  EstimatePose(options.first_frame_timeout_s);
}

RealCell::~RealCell() {
  if (guarded_arm_ != nullptr) {
    try {
      guarded_arm_->Stop();
    } catch (const std::exception&) {
      // The robot is gone already; its controller stopped it when the commands stopped.
    }
  }
  // Members go in reverse order: the watchdog thread, the arm, the beacon thread, the camera's.
}

void RealCell::OpenCamera(const RealCellOptions& options) {
  const std::string& device = profile_.camera.device;
  camera::OpenCameraOptions open;
  // A recorded scene (video, frames) replayed as the cell's camera keeps going like a live one.
  open.loop = true;
  try {
    if (profile_.camera.calibration) {
      const camera::CameraCalibration calibration =
          camera::ReadCameraCalibration(*profile_.camera.calibration);
      intrinsics_ = calibration.ToIntrinsics();
      open.undistort = calibration;
    }
    std::unique_ptr<devices::Camera> camera;
    if (device.rfind(kTwinCameraPrefix, 0) == 0) {
      camera = OpenTwinCamera(device.substr(std::char_traits<char>::length(kTwinCameraPrefix)));
      camera_kind_ = "digital twin";
    } else {
      camera_kind_ = CameraKindName(camera::ClassifyCameraSource(device));
      camera = camera::OpenCamera(device, open);
    }
    grabber_ = std::make_unique<FrameGrabber>(std::move(camera), device, options.camera);
  } catch (const UserError& e) {
    throw UserError("camera " + device + ": " + e.what());
  }
}

std::unique_ptr<devices::Camera> RealCell::OpenTwinCamera(const std::string& layout) const {
  if (!profile_.robot) {
    throw UserError("a digital twin draws the profile's robot, and the profile names none");
  }
  TwinCameraOptions twin;
  twin.layout_file = layout;
  twin.robot_host = profile_.robot->host;
  twin.rtde_port = profile_.robot->rtde_port;
  if (intrinsics_) {  // the size the calibration describes
    twin.width = intrinsics_->width;
    twin.height = intrinsics_->height;
  }
  ReadTwinLayout(layout);  // a bad layout is the profile's error now, not a camera that fails
  return std::make_unique<TwinCamera>(twin, clock_);
}

void RealCell::EstimatePose(double timeout_s) {
  if (!intrinsics_) {
    camera_pose_error_ =
        "the profile gives no camera calibration: frames are used as they come, and the "
        "camera's pose in the table frame is unknown";
    return;
  }
  try {
    const std::vector<camera::TableTag> table_tags = camera::ReadTableTags(profile_.table_tags);
    const auto frame = grabber_->WaitForFrame(-1, timeout_s);
    if (frame == nullptr) {
      const std::string why = grabber_->error();
      throw UserError("no frame from camera " + profile_.camera.device + " within " +
                      std::to_string(timeout_s) + " s" + (why.empty() ? "" : ": " + why));
    }
    tags::TagDetector detector;
    camera_pose_ =
        camera::EstimateCameraPose(*intrinsics_, table_tags, detector.Detect(frame->image));
  } catch (const std::exception& e) {
    camera_pose_error_ = e.what();
  }
}

void RealCell::OpenRobot(const RealCellOptions& options) {
  robot::UrArm::Options arm;
  arm.host = profile_.robot->host;
  arm.rtde_port = profile_.robot->rtde_port;
  arm.script_port = profile_.robot->script_port;
  arm.timeout_s = options.robot_timeout_s;
  safety::SafetyLimits limits = options.limits;
  limits.base_in_table = profile_.robot_base_in_table;
  try {
    ur_arm_ = std::make_unique<robot::UrArm>(arm);
    guarded_arm_ = std::make_unique<safety::GuardedArm>(*ur_arm_, limits, clock_);
  } catch (const UserError& e) {
    throw UserError("robot " + arm.host + ": " + e.what());
  }
  watchdog_ = std::make_unique<safety::ArmWatchdog>(*guarded_arm_);
}

devices::BeaconSource& RealCell::beacons() { return *beacons_; }

std::vector<CellDeviceStatus> RealCell::Status() const {
  std::vector<CellDeviceStatus> rows;
  CellDeviceStatus camera{"camera", camera_kind_, profile_.camera.device, false, ""};
  camera.last_error = grabber_->error();
  camera.connected = camera.last_error.empty() && grabber_->frames_captured() > 0;
  if (camera.last_error.empty() && !camera.connected) camera.last_error = "no frame yet";
  rows.push_back(camera);
  const std::string beacon_kind =
      std::string("DWM1001 (") + uwb::Dwm1001ModeName(profile_.beacons.mode) + ")";
  for (const uwb::BeaconPortStatus& port : beacons_->PortStatus()) {
    rows.push_back({"beacons", beacon_kind, port.port, port.connected, port.last_error});
  }
  if (guarded_arm_ != nullptr) {
    CellDeviceStatus arm{"arm", "UR5 (RTDE + URScript)", profile_.robot->host, true, ""};
    try {
      guarded_arm_->State();
    } catch (const std::exception& e) {
      arm.connected = false;
      arm.last_error = e.what();
    }
    rows.push_back(arm);
  }
  return rows;
}

std::unique_ptr<RealCellWorld> MakeRealCellWorld(RealCell& cell, RealCellWorldOptions options) {
  if (cell.arm() == nullptr) {
    throw UserError(cell.profile().path +
                    ": the profile names no robot, and the tabletop task needs one to teach");
  }
  if (options.camera_name.empty()) options.camera_name = cell.profile().camera.device;
  if (options.beacons_name.empty()) {
    std::string ports;
    for (const std::string& port : cell.profile().beacons.ports) {
      ports += (ports.empty() ? "" : ", ") + port;
    }
    options.beacons_name = "DWM1001 beacons on " + ports;
  }
  if (options.arm_name.empty()) options.arm_name = "UR5 at " + cell.profile().robot->host;
  return std::make_unique<RealCellWorld>(cell.camera(), cell.beacons(), *cell.arm(), cell.clock(),
                                         std::move(options));
}

}  // namespace recon::cell
