#pragma once

#include <Eigen/Core>
#include <vector>

#include "devices/tags/pinhole_camera.h"
#include "engine/store/manifest.h"
#include "engine/worlds/orbit_camera.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/tabletop.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// A beacon of the session as the Beacons screen shows it: its name, the object it is assigned
/// to, what it measures and its latest `reading` (no pixel, rate or noise: the cell's to fill).
ui::BeaconView BeaconViewOf(const BeaconSpec& beacon, const store::SessionManifest& manifest,
                            const std::vector<float>& reading);

/// Fills the snapshot's live view of the tabletop cell: the top camera at width x height, the
/// objects a beacon can be assigned to (where the camera sees them) and each beacon of the
/// session with its latest `reading` drawn where it projects.
void ShowTabletopView(worlds::Tabletop& world, worlds::SceneRenderer& renderer, int width,
                      int height, const store::SessionManifest& manifest,
                      const std::vector<float>& reading, ui::StudioSnapshot& snapshot);

/// Where the teacher's 3-D view looks from until they turn it: from the robot's right, a little
/// above the table, where the gripper coming down onto the toast is not hidden by the arm.
worlds::OrbitCamera DefaultTeacherView();

/// Fills the snapshot's teacher view of the tabletop cell: `camera`'s image at width x height,
/// with shadows, the grip point's drop line to the table and a disc where it meets it, and where
/// the image shows the grip point and the line's foot.
void ShowTeacherView(worlds::Tabletop& world, worlds::SceneRenderer& renderer,
                     const worlds::OrbitCamera& camera, int width, int height,
                     ui::StudioSnapshot& snapshot);

/// The tabletop's grip readout: the state of the grip on the toast and the grasp heights.
ui::GripView GripViewOf(const worlds::Tabletop& world);

}  // namespace recon::studio

namespace recon::studio {

/// The grip point's velocity in the table frame for a teleop input given relative to a camera
/// view that sees the grip point (a real cell's, located by its table tags): the arrows move the
/// arm the way the teacher sees it move on screen, whatever way the camera is mounted.
/// `speed_m_s` at full deflection.
Eigen::Vector3d TeleopVelocity(const tags::PinholeCamera& camera, const Eigen::Vector3d& grip,
                               const ui::TeleopInput& input, double speed_m_s);
/// The same for the teacher's 3-D view: right and up move the grip along the table the way the
/// view looks right and away, whatever its elevation (a flat move never dives into the table).
Eigen::Vector3d TeleopVelocity(const worlds::OrbitCamera& camera, const ui::TeleopInput& input,
                               double speed_m_s);

}  // namespace recon::studio
