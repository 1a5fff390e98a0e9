#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/core/image.h"
#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/orbit_camera.h"

namespace recon::worlds {

/// Something drawn into one frame for a person and not part of the scene (no physics, never in
/// a policy's image): a line, drawn as a thin cylinder from `from` to `to`, or a flat disc lying
/// at `from`.
struct SceneMarker {
  enum class Shape { kLine, kDisc };
  Shape shape = Shape::kLine;
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
  double radius_m = 0.003;
  std::array<float, 4> rgba = {1, 1, 1, 1};
};

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

  /// Renders `scene` for a person: from `camera` (a free camera), with shadows cast by the
  /// scene's lights (a depth cue) and `markers` drawn in. Slower than Render; not for policies.
  /// Throws UserError for a size above the scene's offscreen buffer.
  virtual RgbImage RenderOrbit(MujocoModel& scene, const OrbitCamera& camera,
                               const std::vector<SceneMarker>& markers, int width, int height) = 0;
};

/// Makes a renderer on the calling thread. Throws UserError when no rendering context can be
/// created (no EGL, no Mesa driver), with what was tried.
using SceneRendererFactory = std::function<std::unique_ptr<SceneRenderer>()>;

}  // namespace recon::worlds
