#include "devices/cell/scene_camera.h"

#include <mujoco/mujoco.h>

#include <Eigen/Core>

#include "engine/core/error.h"

namespace recon::cell {

tags::PinholeCamera SceneCamera(const worlds::MujocoModel& scene, const std::string& camera,
                                int width, int height) {
  const mjModel* m = scene.model();
  const mjData* d = scene.data();
  const int id = mj_name2id(m, mjOBJ_CAMERA, camera.c_str());
  if (id < 0) throw UserError("the MuJoCo scene has no camera \"" + camera + "\"");
  // cam_xmat is row-major; Eigen is column-major by default.
  const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> rotation(d->cam_xmat +
                                                                                9 * id);
  const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 1>> position(d->cam_xpos + 3 * id);
  return tags::PinholeCamera::FromMujoco(m->cam_fovy[id], width, height, position, rotation);
}

tags::PinholeCamera OrbitSceneCamera(const worlds::MujocoModel& scene,
                                     const worlds::OrbitCamera& camera, int width, int height) {
  const worlds::OrbitCamera c = camera.Clamped();
  return tags::PinholeCamera::FromMujoco(scene.model()->vis.global.fovy, width, height,
                                         c.Position(), c.Rotation());
}

}  // namespace recon::cell
