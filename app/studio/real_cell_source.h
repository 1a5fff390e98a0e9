#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "devices/cell/real_cell.h"
#include "engine/store/manifest.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/teach/recorder.h"
#include "engine/worlds/world.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// The studio's real cell (recon-studio --cell PROFILE): the devices a cell profile names, opened
/// once for the studio's life (cell::RealCell), and what the studio shows and drives of them:
/// the live camera with the beacons and the grip drawn where the located camera sees them, the
/// devices' live status, the teleop as joint velocities for the real arm (resolved rate over the
/// UR5 kinematics, then the safety envelope), and the e-stop on the guarded arm. Cell thread only,
/// except EmergencyStop (any thread).
class RealCellSource {
 public:
  /// Reads the profile and opens its devices; UserError naming the file, field or device.
  explicit RealCellSource(const std::string& profile_path);

  cell::RealCell& cell() { return *cell_; }

  /// What a new session records about this cell: cell "real" and its devices.
  void DescribeInto(store::SessionManifest& manifest) const;
  /// The tabletop task over the devices, for a session with `manifest` (its image size and
  /// placement), with the UWB -> table transform of `calibration_path` when one exists.
  std::unique_ptr<worlds::World> MakeWorld(const store::SessionManifest& manifest,
                                           const std::string& calibration_path);

  /// The live camera frame, the beacons of `manifest` with `reading` (drawn where they are when
  /// `reading_in_table`: x, y on the table), the task's objects (not located: the list assigns
  /// them) and the grip point.
  void ShowLive(const store::SessionManifest& manifest, const std::vector<float>& reading,
                bool reading_in_table, ui::StudioSnapshot& s) const;
  /// Replaces the snapshot's camera, beacon and arm rows by the devices' live status.
  void ShowDevices(ui::StudioSnapshot& s) const;
  /// The guarded arm's envelope, its counts and its e-stop (the arm's own latch).
  void ShowSafety(ui::SafetyView& view) const;

  /// The grip point's table velocity for a teleop input given on the camera view: through the
  /// located camera, or along the table's axes (right +x, up +y) when the camera has no pose.
  Eigen::Vector3d TeleopVelocity(const ui::TeleopInput& input, double speed_m_s) const;
  /// A person's teacher for the real arm: *command's grip velocity as joint velocities.
  teach::Teacher Teacher(const teach::TeleopCommand* command);

  void EmergencyStop(bool engage, const std::string& reason);
  /// The plate beacon's newest UWB position, when the cell is not calibrated yet (the Beacons
  /// screen shows that it reports); empty when nothing new arrived.
  std::vector<float> RawBeaconReading();

 private:
  Eigen::Vector3d GripPoint() const;

  std::unique_ptr<cell::RealCell> cell_;
};

}  // namespace recon::studio
