#include "devices/cell/twin_scene.h"

#include <mujoco/mujoco.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "devices/cell/scene_camera.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/worlds/scene_assets.h"
#include "engine/worlds/tag_textures.h"

namespace recon::cell {

namespace {

using json = nlohmann::json;

constexpr char kScene[] = "tabletop";
// The table top's extent (assets/mjcf/tabletop.xml): 1.0 m along x from the arm's base, 1.2 m
// along y about it.
constexpr double kTableMinX = 0.0, kTableMaxX = 1.0, kTableHalfY = 0.6;
// A tag geom is a 6 cm textured square whose black border is 0.8 of it.
constexpr double kBorderFraction = 0.8;
constexpr const char* kCornerTags[] = {"tag_corner_0", "tag_corner_1", "tag_corner_2",
                                       "tag_corner_3"};

int Require(const mjModel* m, mjtObj type, const char* name) {
  const int id = mj_name2id(m, type, name);
  if (id < 0) throw UserError(std::string("the tabletop scene has no ") + name);
  return id;
}

Eigen::Vector2d ReadPosition(const json& value, const std::string& path, const char* object) {
  if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number()) {
    throw UserError(path + ": " + object + ": expected [x, y] in metres");
  }
  const Eigen::Vector2d p(value[0].get<double>(), value[1].get<double>());
  CheckOnTable(p, path + ": " + object);
  return p;
}

}  // namespace

void CheckOnTable(const Eigen::Vector2d& p, const std::string& what) {
  if (!p.allFinite() || p.x() < kTableMinX || p.x() > kTableMaxX || std::abs(p.y()) > kTableHalfY) {
    throw UserError(what + ": (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                    ") is off the table (x 0 to 1 m, y -0.6 to 0.6 m)");
  }
}

TwinLayout ReadTwinLayout(const std::string& path) {
  const std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError(path + ": cannot read the twin's layout (missing or unreadable)");
  json root;
  try {
    root = json::parse(*text);
  } catch (const json::parse_error& e) {
    throw UserError(path + ": not valid JSON (" + e.what() + ")");
  }
  if (!root.is_object()) throw UserError(path + ": expected a JSON object (a twin layout)");
  TwinLayout layout;
  for (const auto& [key, value] : root.items()) {
    if (key == "plate") {
      layout.plate = ReadPosition(value, path, "plate");
    } else if (key == "bowl") {
      layout.bowl = ReadPosition(value, path, "bowl");
    } else if (key == "toast") {
      layout.toast = ReadPosition(value, path, "toast");
    } else {
      throw UserError(path + ": " + key + ": unknown object (known: plate, bowl, toast)");
    }
  }
  return layout;
}

void WriteTwinLayout(const std::string& path, const TwinLayout& layout) {
  const json root = {{"plate", {layout.plate.x(), layout.plate.y()}},
                     {"bowl", {layout.bowl.x(), layout.bowl.y()}},
                     {"toast", {layout.toast.x(), layout.toast.y()}}};
  WriteFileAtomically(path, root.dump(2) + "\n");
}

TwinScene::TwinScene() : scene_(worlds::LoadScene(kScene)), arm_(scene_) {
  // A lab's camera sees a 3.5 cm beacon tag across a 1.2 m table at 1280 px well; at the
  // policy scene's 640 px it is 14 px, which the detector misses at some places. This copy of
  // the scene alone gets the larger offscreen buffer (the renderer sizes it per model).
  scene_.mutable_model()->vis.global.offwidth = kMaxWidth;
  scene_.mutable_model()->vis.global.offheight = kMaxHeight;
  worlds::PaintTagTextures(scene_);
  arm_.Reset(worlds::Ur5Arm::kHome);
  Arrange(TwinLayout{});
}

void TwinScene::Arrange(const TwinLayout& layout) {
  const mjModel* m = scene_.model();
  mjData* d = scene_.data();
  for (const auto& [name, p] : {std::pair{"plate", layout.plate}, std::pair{"bowl", layout.bowl}}) {
    mjtNum* pos = d->mocap_pos + 3 * m->body_mocapid[Require(m, mjOBJ_BODY, name)];
    pos[0] = p.x();
    pos[1] = p.y();
  }
  held_offset_.reset();
  const int toast = Require(m, mjOBJ_BODY, "toast");
  PlaceToast({layout.toast.x(), layout.toast.y(), m->body_pos[3 * toast + 2]});
}

void TwinScene::PlaceToast(const Eigen::Vector3d& p) {
  // The toast is a free body: its joint's position, lying flat.
  const mjModel* m = scene_.model();
  mjData* d = scene_.data();
  mjtNum* q = d->qpos + m->jnt_qposadr[m->body_jntadr[Require(m, mjOBJ_BODY, "toast")]];
  q[0] = p.x();
  q[1] = p.y();
  q[2] = p.z();
  q[3] = 1;
  q[4] = q[5] = q[6] = 0;
  mj_forward(m, d);
}

Eigen::Vector3d TwinScene::ToastPosition() const {
  const mjModel* m = scene_.model();
  const mjtNum* q =
      scene_.data()->qpos + m->jnt_qposadr[m->body_jntadr[Require(m, mjOBJ_BODY, "toast")]];
  return {q[0], q[1], q[2]};
}

void TwinScene::PoseArm(const worlds::Ur5Joints& q, double gripper_opening) {
  arm_.ShowPose(q, gripper_opening);  // runs mj_forward: the grip point is where q puts it
  const bool closed = std::isfinite(gripper_opening) && gripper_opening < 0.5;
  const Eigen::Vector3d grip = arm_.GripPosition();
  if (closed && !closed_ && !held_offset_) {
    const Eigen::Vector3d toast = ToastPosition();
    const Eigen::Vector3d offset = toast - grip;
    if (offset.head<2>().norm() <= kGraspReach_m && -offset.z() <= kGraspReach_m) {
      held_offset_ = offset;
    }
  }
  if (!closed && held_offset_) {
    // Let go: it falls straight down onto what is under it.
    const mjModel* m = scene_.model();
    const int toast = Require(m, mjOBJ_BODY, "toast");
    const double rest_z = m->body_pos[3 * toast + 2];  // lying on the table
    const Eigen::Vector3d at = grip + *held_offset_;
    const mjtNum* plate =
        scene_.data()->mocap_pos + 3 * m->body_mocapid[Require(m, mjOBJ_BODY, "plate")];
    const int plate_geom = Require(m, mjOBJ_GEOM, "plate");
    const double plate_radius = m->geom_size[3 * plate_geom];
    const double plate_top = 2 * m->geom_size[3 * plate_geom + 1];
    const bool on_plate = std::hypot(at.x() - plate[0], at.y() - plate[1]) <= plate_radius;
    held_offset_.reset();
    PlaceToast({at.x(), at.y(), rest_z + (on_plate ? plate_top : 0.0)});
  } else if (held_offset_) {
    PlaceToast(grip + *held_offset_);
  }
  closed_ = closed;
}

Eigen::Vector3d TwinScene::BeaconPosition() const {
  const mjtNum* p = scene_.data()->site_xpos + 3 * Require(scene_.model(), mjOBJ_SITE, "beacon");
  return {p[0], p[1], p[2]};
}

tags::PinholeCamera TwinScene::TopCamera(int width, int height) const {
  return SceneCamera(scene_, "top", width, height);
}

std::vector<camera::TableTag> TwinScene::TableTags() const {
  const mjModel* m = scene_.model();
  std::vector<camera::TableTag> tags;
  for (int i = 0; i < 4; ++i) {
    const int geom = Require(m, mjOBJ_GEOM, kCornerTags[i]);
    camera::TableTag tag;
    tag.id = i;
    tag.center_table_m = {m->geom_pos[3 * geom], m->geom_pos[3 * geom + 1],
                          m->geom_pos[3 * geom + 2]};
    tag.size_m = 2 * m->geom_size[3 * geom] * kBorderFraction;
    tags.push_back(tag);
  }
  return tags;
}

double TwinScene::BeaconTagSize() const {
  const mjModel* m = scene_.model();
  return 2 * m->geom_size[3 * Require(m, mjOBJ_GEOM, "tag_beacon")] * kBorderFraction;
}

double TwinScene::BeaconTagHeight() const { return BeaconPosition().z(); }

}  // namespace recon::cell
