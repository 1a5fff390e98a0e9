#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/core/image.h"
#include "engine/worlds/mujoco_model.h"

namespace recon::worlds {

/// Draws what a camera of a MuJoCo scene sees. The engine only knows this interface; the
/// implementation (devices/render: an offscreen EGL context and MuJoCo's renderer) is handed in
/// by the application, so worlds that observe images never touch OpenGL.
///
/// A renderer is bound to the thread that created it (an OpenGL context is current on one
/// thread at a time); parallel experiments make one per worker through a SceneRendererFactory.
class SceneRenderer {
 public:
  virtual ~SceneRenderer() = default;

  /// Renders the current state of `scene` (positions as last computed by mj_forward/mj_step)
  /// from the camera named `camera` at width x height pixels. Throws UserError for an unknown
  /// camera or a size above the scene's offscreen buffer (<visual><global offwidth offheight>).
  virtual RgbImage Render(MujocoModel& scene, const std::string& camera, int width, int height) = 0;
};

/// Makes a renderer on the calling thread. Throws UserError when no rendering context can be
/// created (no EGL, no Mesa driver), with what was tried.
using SceneRendererFactory = std::function<std::unique_ptr<SceneRenderer>()>;

}  // namespace recon::worlds
