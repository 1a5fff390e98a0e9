#include "devices/render/mujoco_renderer.h"

#include <GL/gl.h>
#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstring>
#include <list>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "devices/render/egl_context.h"
#include "engine/core/error.h"

namespace recon::render {

namespace {

// Room for every geom of the project's scenes plus the decorations MuJoCo adds; mjv_updateScene
// warns (and drops geoms) beyond it.
constexpr int kMaxSceneGeoms = 2000;

// MuJoCo loads its OpenGL function pointers into process-wide variables when making a context;
// two renderers starting on two threads must not do that at the same time.
std::mutex make_context_mutex;

std::string ModelName(const mjModel* m) { return m->names != nullptr ? m->names : ""; }

std::string CameraNames(const mjModel* m) {
  if (m->ncam == 0) return "it has no cameras";
  std::string names;
  for (int i = 0; i < m->ncam; ++i) {
    const char* name = mj_id2name(m, mjOBJ_CAMERA, i);
    names += (i == 0 ? "" : ", ") + (name != nullptr && *name != '\0'
                                         ? "\"" + std::string(name) + "\""
                                         : "#" + std::to_string(i) + " (unnamed)");
  }
  return "its cameras are " + names;
}

void ClearGlErrors() {
  // glGetError reports (and clears) one error flag per call; there are only a handful of flags.
  for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i) {
  }
}

std::string Hex(unsigned value) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%04X", value);
  return text;
}

/// What identifies the model MuJoCo's GPU copy was made from. The pointer alone could be reused
/// by a later model after the first is freed; its buffer's address and size as well are unlikely
/// to be.
struct ModelKey {
  const mjModel* model = nullptr;
  const void* buffer = nullptr;
  int buffer_size = 0;

  bool operator==(const ModelKey&) const = default;
  static ModelKey Of(const mjModel* m) { return {m, m->buffer, m->nbuffer}; }
};

}  // namespace

// MuJoCo's scene and GPU copy of one model.
struct ModelResources {
  ModelKey key;
  mjvScene scene;
  mjrContext context;

  ModelResources() {
    mjv_defaultScene(&scene);
    mjr_defaultContext(&context);
  }
  void Free() {
    std::lock_guard lock(make_context_mutex);
    mjr_freeContext(&context);
    mjv_freeScene(&scene);
  }
};

// Worlds rendered from one thread share a renderer (MujocoRendererFactory), and an experiment
// evaluates up to a few dozen worlds in lockstep, each with its own model: keep that many GPU
// copies rather than remaking one per frame.
constexpr size_t kMaxCachedModels = 48;

struct MujocoRenderer::State {
  EglContext egl;  // first member: made first, destroyed last
  mjvOption option;
  mjvCamera camera;
  mjvPerturb perturb;
  std::list<ModelResources> models;      // most recently used first
  std::vector<unsigned char> bottom_up;  // mjr_readPixels' rows, reused between frames

  State() {
    mjv_defaultOption(&option);
    mjv_defaultCamera(&camera);
    mjv_defaultPerturb(&perturb);
  }

  void FreeAll() {
    for (ModelResources& r : models) r.Free();
    models.clear();
  }

  /// MuJoCo's scene and GPU context for `m`, made unless cached.
  ModelResources& Prepare(const mjModel* m) {
    const ModelKey key = ModelKey::Of(m);
    for (auto it = models.begin(); it != models.end(); ++it) {
      if (it->key == key) {
        models.splice(models.begin(), models, it);
        return models.front();
      }
    }
    if (models.size() >= kMaxCachedModels) {
      models.back().Free();
      models.pop_back();
    }
    // A failed earlier attempt (see the catch below) leaves OpenGL errors that mjr_makeContext
    // would blame on itself in a warning.
    ClearGlErrors();
    models.emplace_front();
    ModelResources& r = models.front();
    try {
      mjv_makeScene(m, &r.scene, kMaxSceneGeoms);
      std::lock_guard lock(make_context_mutex);
      // The font is never drawn into camera images: the smallest one is the cheapest to make.
      mjr_makeContext(m, &r.context, mjFONTSCALE_50);
    } catch (...) {
      r.Free();
      models.pop_front();
      ClearGlErrors();
      throw;
    }
    // mjv_makeScene resets the flags; these two are most of llvmpipe's time per small frame.
    r.scene.flags[mjRND_SHADOW] = 0;
    r.scene.flags[mjRND_REFLECTION] = 0;
    r.key = key;
    return r;
  }
};

MujocoRenderer::MujocoRenderer() {
  worlds::InstallMujocoErrorHandlers();
  // Contexts are made and destroyed one at a time: Mesa's llvmpipe crashed (a general protection
  // fault in swrast_dri.so, once in a dozen experiments) while two threads made and dropped
  // contexts side by side.
  std::lock_guard lock(make_context_mutex);
  state_ = std::make_unique<State>();
}

MujocoRenderer::~MujocoRenderer() {
  // mjr_freeContext deletes OpenGL objects, so our context must be current for it.
  try {
    ScopedCurrent current(state_->egl);
    state_->FreeAll();
  } catch (const std::exception&) {
    // The context is current on another thread: destroying it frees its OpenGL objects anyway;
    // only MuJoCo's CPU-side memory is left to free, and that needs no context.
    for (ModelResources& r : state_->models) mjv_freeScene(&r.scene);
  }
  std::lock_guard lock(make_context_mutex);
  state_.reset();
}

const std::string& MujocoRenderer::context_description() const { return state_->egl.description(); }

namespace {

/// UserError unless width x height fits the scene's offscreen buffer; `what` names the view.
void CheckSize(const mjModel* m, int width, int height, const std::string& what) {
  const int max_width = m->vis.global.offwidth, max_height = m->vis.global.offheight;
  if (width <= 0 || height <= 0 || width > max_width || height > max_height) {
    throw UserError("cannot render a " + std::to_string(width) + "x" + std::to_string(height) +
                    " image from " + what + " of MuJoCo scene \"" + ModelName(m) +
                    "\": its offscreen buffer is " + std::to_string(max_width) + "x" +
                    std::to_string(max_height) +
                    " (raise <visual><global offwidth=\"..\" offheight=\"..\"/>)");
  }
}

/// Adds `marker` to the scene's geoms (decorations: no physics, not selectable); false when the
/// scene has no room left.
bool AddMarker(const worlds::SceneMarker& marker, mjvScene& scene) {
  if (scene.ngeom >= scene.maxgeom) return false;
  mjvGeom& g = scene.geoms[scene.ngeom];
  const float rgba[4] = {marker.rgba[0], marker.rgba[1], marker.rgba[2], marker.rgba[3]};
  if (marker.shape == worlds::SceneMarker::Shape::kDisc) {
    // mjv_initGeom takes a model geom's sizes: a cylinder's radius, then its half-height.
    const mjtNum size[3] = {marker.radius_m, 0.0005, 0};
    const mjtNum pos[3] = {marker.from.x(), marker.from.y(), marker.from.z()};
    const mjtNum identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    mjv_initGeom(&g, mjGEOM_CYLINDER, size, pos, identity, rgba);
  } else {
    mjv_initGeom(&g, mjGEOM_CYLINDER, nullptr, nullptr, nullptr, rgba);
    mjv_makeConnector(&g, mjGEOM_CYLINDER, marker.radius_m, marker.from.x(), marker.from.y(),
                      marker.from.z(), marker.to.x(), marker.to.y(), marker.to.z());
  }
  g.category = mjCAT_DECOR;
  g.objtype = mjOBJ_UNKNOWN;
  g.objid = -1;
  ++scene.ngeom;
  return true;
}

}  // namespace

RgbImage MujocoRenderer::Render(worlds::MujocoModel& scene, const std::string& camera, int width,
                                int height) {
  const mjModel* m = scene.model();
  const int camera_id = mj_name2id(m, mjOBJ_CAMERA, camera.c_str());
  if (camera_id < 0) {
    throw UserError("MuJoCo scene \"" + ModelName(m) + "\" has no camera \"" + camera + "\"; " +
                    CameraNames(m));
  }
  CheckSize(m, width, height, "camera \"" + camera + "\"");
  State& s = *state_;
  s.camera.type = mjCAMERA_FIXED;
  s.camera.fixedcamid = camera_id;
  return Draw(scene, {}, false, width, height, "camera \"" + camera + "\"");
}

RgbImage MujocoRenderer::RenderOrbit(worlds::MujocoModel& scene, const worlds::OrbitCamera& camera,
                                     const std::vector<worlds::SceneMarker>& markers, int width,
                                     int height) {
  CheckSize(scene.model(), width, height, "the free camera");
  State& s = *state_;
  const worlds::OrbitCamera c = camera.Clamped();
  s.camera.type = mjCAMERA_FREE;
  for (int i = 0; i < 3; ++i) s.camera.lookat[i] = c.lookat[i];
  s.camera.distance = c.distance_m;
  s.camera.azimuth = c.azimuth_deg;
  s.camera.elevation = c.elevation_deg;
  return Draw(scene, markers, true, width, height, "the free camera");
}

RgbImage MujocoRenderer::Draw(worlds::MujocoModel& scene,
                              const std::vector<worlds::SceneMarker>& markers, bool shadows,
                              int width, int height, const std::string& what) {
  const mjModel* m = scene.model();
  State& s = *state_;
  ScopedCurrent current(s.egl);
  ModelResources& r = s.Prepare(m);
  mjv_updateScene(m, scene.data(), &s.option, &s.perturb, &s.camera, mjCAT_ALL, &r.scene);
  for (const worlds::SceneMarker& marker : markers) {
    if (!AddMarker(marker, r.scene)) break;
  }
  // A person's view casts shadows from the scene's lights (not the headlight, which moves with
  // the camera): the gripper's shadow on the table says how high it is. Policies' images keep
  // them off (Prepare), which is most of llvmpipe's time per small frame.
  r.scene.flags[mjRND_SHADOW] = shadows ? 1 : 0;
  for (int i = 0; i < r.scene.nlight; ++i) {
    if (!r.scene.lights[i].headlight) r.scene.lights[i].castshadow = shadows ? 1 : 0;
  }

  const mjrRect viewport = {0, 0, width, height};
  std::unique_lock draw_lock(PixelReadbackMutex());
  mjr_setBuffer(mjFB_OFFSCREEN, &r.context);
  if (r.context.currentBuffer != mjFB_OFFSCREEN) {
    throw std::runtime_error("MuJoCo has no offscreen buffer for scene \"" + ModelName(m) + "\"");
  }
  mjr_render(viewport, &r.scene, &r.context);
  // Rows of 3 * width bytes are not 4-byte aligned for every width, and OpenGL pads read rows to
  // 4 bytes by default; MuJoCo 2.2 happens to set 1 itself, the buffer size below relies on it.
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  const size_t row_bytes = static_cast<size_t>(width) * 3;
  s.bottom_up.resize(row_bytes * height);
  mjr_readPixels(s.bottom_up.data(), nullptr, viewport, &r.context);
  const GLenum error = glGetError();
  draw_lock.unlock();
  if (error != GL_NO_ERROR) {
    throw std::runtime_error("OpenGL error " + Hex(error) + " while rendering " + what +
                             " of MuJoCo scene \"" + ModelName(m) + "\"");
  }

  RgbImage image;
  image.width = width;
  image.height = height;
  image.rgb.resize(row_bytes * height);
  // OpenGL reads rows bottom-up; images are stored top row first.
  for (int row = 0; row < height; ++row) {
    std::memcpy(image.rgb.data() + row * row_bytes,
                s.bottom_up.data() + (height - 1 - row) * row_bytes, row_bytes);
  }
  return image;
}

namespace {

// A handle on the calling thread's shared renderer: worlds made on one thread (an experiment's
// worker evaluates 20 at once) share one EGL context instead of making one each.
class SharedRenderer final : public worlds::SceneRenderer {
 public:
  SharedRenderer() {
    thread_local std::weak_ptr<MujocoRenderer> shared;
    renderer_ = shared.lock();
    if (renderer_ == nullptr) {
      renderer_ = std::make_shared<MujocoRenderer>();
      shared = renderer_;
    }
  }
  RgbImage Render(worlds::MujocoModel& scene, const std::string& camera, int width,
                  int height) override {
    return renderer_->Render(scene, camera, width, height);
  }
  RgbImage RenderOrbit(worlds::MujocoModel& scene, const worlds::OrbitCamera& camera,
                       const std::vector<worlds::SceneMarker>& markers, int width,
                       int height) override {
    return renderer_->RenderOrbit(scene, camera, markers, width, height);
  }

 private:
  std::shared_ptr<MujocoRenderer> renderer_;
};

}  // namespace

worlds::SceneRendererFactory MujocoRendererFactory() {
  return
      []() -> std::unique_ptr<worlds::SceneRenderer> { return std::make_unique<SharedRenderer>(); };
}

bool HeadlessRenderingAvailable(std::string* why) {
  try {
    EglContext probe;
    if (why != nullptr) why->clear();
    return true;
  } catch (const UserError& e) {
    if (why != nullptr) *why = e.what();
    return false;
  }
}

}  // namespace recon::render
