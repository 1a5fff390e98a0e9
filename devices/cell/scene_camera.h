#pragma once

#include <string>

#include "devices/tags/pinhole_camera.h"
#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/orbit_camera.h"

namespace recon::cell {

/// The pinhole model of camera `camera` of a MuJoCo scene in its current state, for images of
/// width x height pixels (positions as last computed by mj_forward/mj_step). What turns a point
/// on the table into the pixel where the simulated camera sees it. Throws UserError for an
/// unknown camera.
tags::PinholeCamera SceneCamera(const worlds::MujocoModel& scene, const std::string& camera,
                                int width, int height);

/// The same for a free camera of the scene (MujocoRenderer::RenderOrbit's images): its field of
/// view is the scene's <visual><global fovy>.
tags::PinholeCamera OrbitSceneCamera(const worlds::MujocoModel& scene,
                                     const worlds::OrbitCamera& camera, int width, int height);

}  // namespace recon::cell
