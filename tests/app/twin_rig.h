#pragma once

// A digital twin of a real cell for the studio's tests: the profile (cell::WriteTwinCell), a
// FakeUrController on loopback TCP, and the plate's beacon, a FakeDwm1001 on a pseudo-terminal
// that reports where the layout puts the plate through a hidden UWB frame. The test is the
// teacher: it moves the objects by rewriting the layout.

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "devices/cell/twin_beacon.h"
#include "devices/cell/twin_cell.h"
#include "devices/cell/twin_scene.h"
#include "devices/robot/fake_ur_controller.h"
#include "engine/calib/calibration.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio::testing {

inline constexpr uint64_t kTwinPlateBeaconId = 0xDECA0000000000A1ull;

/// The installation's UWB frame in the studio's twin tests: anchors 2 m off, turned 30 degrees.
inline calib::RigidTransform TwinUwbFrame() {
  return {Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()).matrix(),
          Eigen::Vector3d(2.0, -1.0, 0.3)};
}

/// A calibration that knows the hidden frame (what a good calibration recovers).
inline calib::CalibrationReport TwinCalibration() {
  std::vector<calib::CalibrationPoint> points;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.3, -0.3, 0.02), Eigen::Vector3d(0.8, -0.2, 0.02),
        Eigen::Vector3d(0.7, 0.3, 0.02), Eigen::Vector3d(0.4, 0.25, 0.02)}) {
    points.push_back({p, TwinUwbFrame().Apply(p)});
  }
  return calib::Calibrate(points);
}

/// The twin's devices and profile in `folder`, the bowl out of the beacon's way.
struct TwinRig {
  explicit TwinRig(const std::filesystem::path& dir) : folder(dir) {
    layout.bowl = {0.12, 0.0};
    scene.Arrange(layout);
    cell::TwinBeaconOptions beacon_options;
    beacon_options.node_id = kTwinPlateBeaconId;
    beacon_options.table_to_uwb = TwinUwbFrame();
    beacon_options.noise_m = 0.01;
    beacon_options.seed = 31;  // the readings' noise
    beacon_options.period_ms = 50;
    beacon = std::make_unique<cell::TwinBeacon>(scene.BeaconPosition(), beacon_options);
    robot = std::make_unique<robot::FakeUrController>();
    cell::TwinCellDevices devices;
    devices.rtde_port = robot->rtde_port();
    devices.script_port = robot->script_port();
    devices.beacon_ports = {beacon->port()};
    devices.beacon_names = {{"0xDECA0000000000A1", "plate"}};
    // The shell's `lec` stream, where a tag without a fix prints a line without a position (in
    // TLV mode the fake answers every request with the last position).
    devices.beacon_mode = "lec";
    profile = cell::WriteTwinCell(folder.string(), devices, layout);
  }
  ~TwinRig() {
    robot.reset();
    beacon.reset();
  }

  /// The teacher puts the plate, the beacon beside it, at table (x, y).
  Eigen::Vector3d PutPlate(double x, double y) {
    layout.plate = {x, y};
    scene.Arrange(layout);
    cell::WriteTwinLayout((folder / "layout.json").string(), layout);
    beacon->MoveTo(scene.BeaconPosition());
    return scene.BeaconPosition();
  }
  /// The teacher sets up the layout a trial asks for.
  void SetUpLayout(const ui::TrialView& trial) {
    for (const ui::TrialView::Object& o : trial.layout) {
      Eigen::Vector2d& place = o.name == "plate"  ? layout.plate
                               : o.name == "bowl" ? layout.bowl
                                                  : layout.toast;
      place = {o.table_m[0], o.table_m[1]};
    }
    PutPlate(layout.plate.x(), layout.plate.y());
  }

  std::filesystem::path folder;
  cell::TwinLayout layout;
  cell::TwinScene scene;
  std::unique_ptr<cell::TwinBeacon> beacon;
  std::unique_ptr<robot::FakeUrController> robot;
  std::string profile;
};

}  // namespace recon::studio::testing
