#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "engine/core/files.h"
#include "engine/devices/camera.h"
#include "engine/devices/clock.h"
#include "engine/worlds/scene_renderer.h"

namespace recon::robot {
class RtdeClient;
}

namespace recon::cell {

class TwinScene;

/// How a TwinCamera is set up.
struct TwinCameraOptions {
  /// The layout file (ReadTwinLayout): where the objects stand. Read again whenever it changes,
  /// so a test, or a person with `recon twin`, moves an object by rewriting it.
  std::string layout_file;
  /// The UR controller whose joints the drawn arm takes (its RTDE interface).
  std::string robot_host = "127.0.0.1";
  int rtde_port = 30004;
  /// Up to TwinScene::kMaxWidth x kMaxHeight.
  int width = 1280, height = 960;
  /// Capture waits for the next frame at this rate, as a camera does (drawing a frame costs
  /// tens of milliseconds of CPU; a free-running twin would take a core from the cell).
  double frame_rate_hz = 15;
};

/// A digital twin's camera: behind the real devices::Camera interface, each Capture draws the
/// tabletop scene from its top camera (TwinScene) with the objects where the layout file puts
/// them and the UR5 at the joints and gripper (tool output 0) its controller reports over RTDE,
/// so the real cell's path (RTDE over TCP, beacons on a serial port, camera frames that follow
/// the arm) runs end to end without hardware. The scene, the renderer and the RTDE connection are
/// made on the first Capture, on the capturing thread (a renderer belongs to its thread). While
/// the controller cannot be reached the arm is drawn where it was last seen (at first: home), as
/// a real camera keeps seeing an arm whose controller went quiet; the connection is retried every
/// second. UserError naming the file for a layout that is missing or wrong.
class TwinCamera final : public devices::Camera {
 public:
  /// `clock` stamps the frames and must outlive the camera.
  TwinCamera(TwinCameraOptions options, const devices::Clock& clock);
  ~TwinCamera() override;
  TwinCamera(const TwinCamera&) = delete;
  TwinCamera& operator=(const TwinCamera&) = delete;

  devices::CameraFrame Capture() override;
  /// E.g. "digital twin of 127.0.0.1:30004, 640x480 (layout.json)".
  std::string Describe() const override;

 private:
  void FollowLayout();
  void FollowArm();

  TwinCameraOptions options_;
  const devices::Clock& clock_;
  std::unique_ptr<TwinScene> scene_;
  std::unique_ptr<worlds::SceneRenderer> renderer_;
  std::unique_ptr<robot::RtdeClient> rtde_;
  double next_connect_s_ = 0;
  std::optional<FileStamp> layout_stamp_;  ///< of the layout file read last
  int64_t next_sequence_ = 0;
  double next_frame_s_ = 0;
};

}  // namespace recon::cell
