#include "devices/cell/twin_camera.h"

#include <algorithm>
#include <chrono>
#include <system_error>
#include <thread>
#include <utility>

#include "devices/cell/twin_scene.h"
#include "devices/render/mujoco_renderer.h"
#include "devices/robot/rtde_client.h"
#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::cell {

namespace {

// UrArm closes the gripper with tool digital output 0: bit 16 of the RTDE output bits.
constexpr uint64_t kGripperBit = uint64_t{1} << 16;
constexpr double kReconnectPeriod_s = 1.0;

}  // namespace

TwinCamera::TwinCamera(TwinCameraOptions options, const devices::Clock& clock)
    : options_(std::move(options)), clock_(clock) {
  if (options_.width < 16 || options_.height < 16 || options_.width > TwinScene::kMaxWidth ||
      options_.height > TwinScene::kMaxHeight) {
    throw UserError("a twin camera draws 16 x 16 to " + std::to_string(TwinScene::kMaxWidth) +
                    " x " + std::to_string(TwinScene::kMaxHeight) + " pixels, not " +
                    std::to_string(options_.width) + " x " + std::to_string(options_.height));
  }
  if (!(options_.frame_rate_hz > 0 && options_.frame_rate_hz <= 120)) {
    throw UserError("a twin camera's frame rate is above 0 and at most 120 Hz");
  }
}

TwinCamera::~TwinCamera() = default;

void TwinCamera::FollowLayout() {
  const std::optional<FileStamp> stamp = StampOf(options_.layout_file);
  if (!stamp) throw UserError(options_.layout_file + ": cannot read the twin's layout (missing)");
  if (layout_stamp_ == stamp) return;
  scene_->Arrange(ReadTwinLayout(options_.layout_file));
  layout_stamp_ = stamp;
}

void TwinCamera::FollowArm() {
  if (rtde_ == nullptr || !rtde_->connected()) {
    const double now = clock_.NowSeconds();
    if (now < next_connect_s_) return;
    next_connect_s_ = now + kReconnectPeriod_s;
    robot::RtdeClient::Options rtde;
    rtde.host = options_.robot_host;
    rtde.port = options_.rtde_port;
    rtde.timeout_s = 0.5;
    rtde.outputs = {"timestamp", "actual_q", "actual_digital_output_bits"};
    try {
      rtde_ = std::make_unique<robot::RtdeClient>(rtde);
      rtde_->WaitForData(0.5);
    } catch (const UserError&) {
      rtde_.reset();  // drawn where it was; tried again in a second
      return;
    }
  }
  if (const std::optional<robot::RtdeState> state = rtde_->Latest()) {
    worlds::Ur5Joints q;
    for (size_t i = 0; i < q.size(); ++i) q[i] = state->actual_q_rad[i];
    scene_->PoseArm(q, (state->digital_output_bits & kGripperBit) != 0 ? 0.0 : 1.0);
  }
}

devices::CameraFrame TwinCamera::Capture() {
  const double wait_s = next_frame_s_ - clock_.NowSeconds();
  if (wait_s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait_s));
  next_frame_s_ = std::max(next_frame_s_, clock_.NowSeconds()) + 1.0 / options_.frame_rate_hz;
  if (scene_ == nullptr) {
    scene_ = std::make_unique<TwinScene>();
    renderer_ = render::MujocoRendererFactory()();
  }
  FollowLayout();
  FollowArm();
  devices::CameraFrame frame;
  frame.image = renderer_->Render(scene_->scene(), "top", options_.width, options_.height);
  frame.timestamp_s = clock_.NowSeconds();
  frame.sequence = next_sequence_++;
  return frame;
}

std::string TwinCamera::Describe() const {
  return "digital twin of " + options_.robot_host + ":" + std::to_string(options_.rtde_port) +
         ", " + std::to_string(options_.width) + "x" + std::to_string(options_.height) + " (" +
         options_.layout_file + ")";
}

}  // namespace recon::cell
