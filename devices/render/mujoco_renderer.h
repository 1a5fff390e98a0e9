#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/worlds/scene_renderer.h"

namespace recon::render {

/// What a camera of a MuJoCo scene sees, drawn by MuJoCo's own renderer into the offscreen
/// buffer of a private EGL context (see egl_context.h). Bound to the thread that made it.
///
/// Tuned for many small images per second rather than looks: shadows and reflections are off
/// (with them, 64x64 frames are about 3x slower on llvmpipe), and scenes are expected to set
/// <quality offsamples="0"/> since multisampling costs as much again.
///
/// MuJoCo's GPU-side copy of a model (mjrContext: textures, meshes, offscreen buffers) costs
/// 12-255 ms to make, so it is made on the first Render of a model and kept (for up to 48 models,
/// least recently used dropped first). A model changed after its first rendering (e.g. a texture
/// painted through MujocoModel::mutable_model()) is not re-uploaded: make such changes before
/// rendering.
class MujocoRenderer final : public worlds::SceneRenderer {
 public:
  /// Makes the EGL context (current on the calling thread). Throws UserError when there is none.
  MujocoRenderer();
  ~MujocoRenderer() override;

  MujocoRenderer(const MujocoRenderer&) = delete;
  MujocoRenderer& operator=(const MujocoRenderer&) = delete;

  RgbImage Render(worlds::MujocoModel& scene, const std::string& camera, int width,
                  int height) override;
  RgbImage RenderOrbit(worlds::MujocoModel& scene, const worlds::OrbitCamera& camera,
                       const std::vector<worlds::SceneMarker>& markers, int width,
                       int height) override;

  /// The OpenGL context in use, for logs ("EGL 1.5 surfaceless; OpenGL 4.5 ... llvmpipe ...").
  const std::string& context_description() const;

 private:
  struct State;  // EGL context and MuJoCo's visualisation structs, kept out of this header
  /// Draws the scene from the camera set in the state, with `markers` and (or without) shadows,
  /// and reads the image back; `what` names the camera in errors.
  RgbImage Draw(worlds::MujocoModel& scene, const std::vector<worlds::SceneMarker>& markers,
                bool shadows, int width, int height, const std::string& what);
  std::unique_ptr<State> state_;
};

/// Makes renderers for the worlds that observe images. All renderers made on one thread share one
/// MujocoRenderer (one EGL context), which lives as long as any of them.
worlds::SceneRendererFactory MujocoRendererFactory();

/// Whether a headless rendering context can be made here (tries to make one and drops it). When
/// not, sets `*why` (if given) to the reason, naming the EGL calls that failed. Tests and the
/// CLI use it to skip or refuse image-based work with a clear message instead of failing later.
bool HeadlessRenderingAvailable(std::string* why = nullptr);

}  // namespace recon::render
