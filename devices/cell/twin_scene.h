#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "devices/camera/table_tags_file.h"
#include "devices/tags/pinhole_camera.h"
#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/ur5_arm.h"

namespace recon::cell {

/// Where a digital twin's objects stand on the table (table frame x, y in metres): what a person
/// set up in front of the real arm. Each stays at the tabletop scene's height.
struct TwinLayout {
  Eigen::Vector2d plate{0.55, 0.35};
  Eigen::Vector2d bowl{0.55, -0.2};
  Eigen::Vector2d toast{0.35, 0.0};
};

/// Reads a layout file, {"plate": [x, y], "bowl": [x, y], "toast": [x, y]} (each optional: the
/// scene's place). UserError naming the file and the field for a missing file, bad JSON, an
/// unknown object, a position that is not two finite numbers or that lies off the table.
TwinLayout ReadTwinLayout(const std::string& path);
/// UserError "<what>: (x, y) is off the table ..." unless `p` lies on the table top.
void CheckOnTable(const Eigen::Vector2d& p, const std::string& what);
/// Writes `layout` as ReadTwinLayout reads it, atomically (a reader sees the old or the new one).
void WriteTwinLayout(const std::string& path, const TwinLayout& layout);

/// The tabletop scene (assets/mjcf/tabletop.xml, its AprilTags painted) as a digital twin of a
/// real cell shows it: the objects where a layout puts them and the UR5 posed kinematically at
/// joint angles that come from elsewhere (a controller's RTDE state). No dynamics are simulated,
/// but the gripper carries the toast kinematically, so a policy's trial on the twin can pick it
/// up and put it down. It is the truth a twin's camera draws and its beacons report. One thread
/// only, like its scene.
class TwinScene {
 public:
  /// The largest image the scene can be drawn at.
  static constexpr int kMaxWidth = 1280, kMaxHeight = 960;

  TwinScene();
  TwinScene(const TwinScene&) = delete;  // the arm points into the scene
  TwinScene& operator=(const TwinScene&) = delete;

  /// Puts the objects where `layout` says (a held toast is let go: the person took it).
  void Arrange(const TwinLayout& layout);
  /// `q` as the controller reports it, `gripper_opening` 0 (closed) to 1 (open). Closing the
  /// gripper with the toast between its fingers (the grip point within kGraspReach_m of the
  /// toast's centre across, and at most that above it) picks the toast up; it then moves with
  /// the grip point; opening the gripper drops it straight down, onto the plate where the plate
  /// is under it, else onto the table.
  void PoseArm(const worlds::Ur5Joints& q, double gripper_opening);
  static constexpr double kGraspReach_m = 0.04;

  Eigen::Vector3d ToastPosition() const;
  bool HoldsToast() const { return held_offset_.has_value(); }

  /// Where the beacon beside the plate is (its tag's centre), table frame.
  Eigen::Vector3d BeaconPosition() const;
  /// The pinhole model of the scene's top camera at width x height pixels.
  tags::PinholeCamera TopCamera(int width, int height) const;
  worlds::MujocoModel& scene() { return scene_; }

  /// The table's corner tags as a table-tags file states them (their ids, centres and sizes read
  /// from the scene): what a real cell's camera pose is estimated from.
  std::vector<camera::TableTag> TableTags() const;
  /// The beacon's tag: id 10, its black border's side, and its face's height over the table.
  static constexpr int kBeaconTagId = 10;
  double BeaconTagSize() const;
  double BeaconTagHeight() const;

 private:
  /// Puts the toast's free body at `p`, lying flat.
  void PlaceToast(const Eigen::Vector3d& p);

  worlds::MujocoModel scene_;
  worlds::Ur5Arm arm_;
  bool closed_ = false;
  std::optional<Eigen::Vector3d> held_offset_;  ///< toast minus grip point while held
};

}  // namespace recon::cell
