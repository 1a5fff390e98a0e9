#pragma once

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "devices/uwb/dwm1001_driver.h"

namespace recon::cell {

/// A camera device that is a digital twin (cell::TwinCamera) rather than a camera:
/// "twin:<layout file>", drawing the tabletop scene with the profile's robot.
constexpr char kTwinCameraPrefix[] = "twin:";

/// The top-down camera of a real cell.
struct CameraProfile {
  /// What camera::OpenCamera opens: a V4L2 device ("/dev/video0", "0"), a video file or a
  /// folder of frames (the fake camera), the latter two resolved against the profile's folder;
  /// or "twin:<layout file>" (kTwinCameraPrefix), the layout resolved the same way.
  std::string device;
  /// The calibration YAML (camera::ReadCameraCalibration), absolute. Without one the camera
  /// delivers raw frames and the cell has no intrinsics, so no camera pose.
  std::optional<std::string> calibration;
};

/// The DWM1001 tags of a real cell (uwb::BeaconHub's options).
struct BeaconsProfile {
  std::vector<std::string> ports;  ///< serial ports; relative ones resolved
  uwb::Dwm1001Mode mode = uwb::Dwm1001Mode::kLecShell;
  /// Beacon names by node id in hex (uwb::BeaconHubOptions::names), e.g. {"0x1A2B", "plate"}.
  std::map<std::string, std::string> names;
};

/// The UR5 of a real cell (robot::UrArm's connection).
struct RobotProfile {
  std::string host;
  int rtde_port = 30004;
  int script_port = 30002;
};

/// The AprilTag on top of the beacon that a calibration moves: what the camera locates it by.
struct BeaconTagProfile {
  int id = 10;
  double size_m = 0.0352;  ///< its black border's side
  double height_m = 0.06;  ///< its face's height over the table
};

/// Everything that describes one real teaching cell, as read from its JSON profile (see
/// docs/hardware.md, "Cell profile"): which devices to open and where the arm stands. Paths in
/// here are absolute or as the user gave a device ("/dev/...").
struct CellProfile {
  std::string path;  ///< the profile file itself, for messages
  CameraProfile camera;
  std::string table_tags;  ///< camera::ReadTableTags file, absolute
  BeaconsProfile beacons;
  /// No robot: a cell with a camera and beacons only (calibration, play data).
  std::optional<RobotProfile> robot;
  /// The arm's base in the table frame. Identity is the simulated cell's convention: the table
  /// frame's origin is the arm's base.
  Eigen::Isometry3d robot_base_in_table = Eigen::Isometry3d::Identity();
  BeaconTagProfile beacon_tag;
  /// Set when the beacon rides on the arm's tool ("beacon_on_arm": {"offset_m": [x, y, z]}, its
  /// antenna from the tool point in the table frame): the Calibrate step then moves the arm to
  /// the places itself (ArmCalibration) instead of asking the teacher to move the beacon.
  std::optional<Eigen::Vector3d> beacon_on_arm_offset_m;
};

/// Reads a cell profile:
///
///     {"camera": {"device": "/dev/video0", "calibration": "camera.yaml"},
///      "table_tags": "table_tags.json",
///      "beacons": {"ports": ["/dev/ttyACM0"], "mode": "tlv", "names": {"0x1A2B": "plate"}},
///      "robot": {"host": "192.168.1.10", "rtde_port": 30004, "script_port": 30002},
///      "robot_base_in_table": {"xyz_m": [0, 0, 0], "yaw_deg": 0},
///      "beacon_tag": {"id": 10, "size_m": 0.0352, "height_m": 0.06},
///      "beacon_on_arm": {"offset_m": [0, 0, 0.03]}}
///
/// camera.calibration, beacons.mode (default "lec"), beacons.names, robot, its ports,
/// robot_base_in_table, beacon_tag (and each of its fields) and beacon_on_arm (which needs a
/// robot) are optional. Relative paths (a
/// camera file or folder, the calibration, the table tags, a serial port) are resolved against the
/// profile's folder. Throws UserError naming the file and the field, e.g. "cell.json:
/// beacons.ports[1]: expected a string", for a missing file, a file that is not JSON, a missing or
/// mistyped field and an unknown mode. The files it names are not opened here (RealCell does that).
CellProfile ReadCellProfile(const std::string& path);

}  // namespace recon::cell
