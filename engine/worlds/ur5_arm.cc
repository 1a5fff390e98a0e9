#include "engine/worlds/ur5_arm.h"

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>

#include "engine/core/error.h"

namespace recon::worlds {

namespace {

constexpr const char* kJointNames[Ur5Arm::kJoints] = {"ur5_shoulder_pan", "ur5_shoulder_lift",
                                                      "ur5_elbow",        "ur5_wrist_1",
                                                      "ur5_wrist_2",      "ur5_wrist_3"};
constexpr const char* kFingerNames[2] = {"ur5_finger_left", "ur5_finger_right"};
constexpr char kGraspPrefix[] = "grasp_";
// A 12 cm stroke (like a Robotiq 2F-140): the toast (9 cm) fits, and a held object shows in the
// finger opening, which the policy reads as part of x.
constexpr double kFingerOpen_m = 0.06;
// Fingers sit 12 mm either side of the grip point and are 8 mm thick (half): a finger at slide
// position s touches an object of half-width w when 0.012 + s - 0.008 = w.
constexpr double kFingerInnerOffset_m = 0.004;
// Where a closing gripper holds an object (GraspOffset). The fingers' inner faces are 64 mm from
// the grip point when open (12 mm offset + 60 mm stroke - 8 mm half-thickness); a finger is 20 mm
// wide and its pad runs 60 mm back from the tip; the pads must grip at least 5 mm of the object.
constexpr double kFingerInnerHalfOpening_m = 0.064;
constexpr double kFingerHalfWidth_m = 0.01;
constexpr double kFingerPadLength_m = 0.06;
constexpr double kMinPadOverlap_m = 0.005;
// The fingers take this long to close: an object that comes into the window meanwhile (the arm
// still settling as the gripper shuts) is caught; after it, fingers closed on nothing stay so.
// (A 2F-style gripper closing at 50 mm/s crosses the 28 mm between its open fingers and a 10 cm
// slice in about 0.6 s.)
constexpr double kFingerClosingTime_s = 0.6;
constexpr double kFingerSpeed_m_s = 0.05;
// Nothing whose centre is farther than this from the grip point is grasped.
constexpr double kGraspReach_m = 0.08;
// The servo's set-point never runs further than this ahead of the joint (a blocked joint must
// not wind up a huge correction).
constexpr double kMaxSetpointLead_rad = 0.2;

int RequireId(const mjModel* m, mjtObj type, const std::string& name, const char* what) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) {
    throw UserError("the scene has no UR5 " + std::string(what) + " named '" + name +
                    "' (include assets/mjcf/ur5.xml)");
  }
  return id;
}

double Clamp(double v, double lo, double hi) { return std::min(hi, std::max(lo, v)); }

/// How far `object` reaches from its centre along the unit direction `axis`: the support of its
/// boxes (or spheres and cylinders, by their radius) in that direction.
double HalfExtent(const MujocoModel& scene, int object, const Eigen::Vector3d& axis) {
  const mjModel* m = scene.model();
  const mjData* d = scene.data();
  double half = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != object) continue;
    const mjtNum* size = m->geom_size + 3 * g;
    const mjtNum* ro = d->geom_xmat + 9 * g;
    double extent = 0;
    if (m->geom_type[g] == mjGEOM_BOX) {
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d column(ro[k], ro[3 + k], ro[6 + k]);
        extent += std::abs(axis.dot(column)) * size[k];
      }
    } else {
      extent = size[0];
    }
    half = std::max(half, extent);
  }
  return half;
}

}  // namespace

void Ur5Arm::ScratchDeleter::operator()(mjData_* d) const { mj_deleteData(d); }

Ur5Arm::Ur5Arm(MujocoModel& scene) : scene_(&scene) {
  const mjModel* m = scene.model();
  ik_data_.reset(mj_makeData(m));
  for (int i = 0; i < kJoints; ++i) {
    const int joint = RequireId(m, mjOBJ_JOINT, kJointNames[i], "joint");
    qpos_adr_[i] = m->jnt_qposadr[joint];
    dof_adr_[i] = m->jnt_dofadr[joint];
    actuator_[i] = RequireId(m, mjOBJ_ACTUATOR, kJointNames[i], "actuator");
  }
  for (int i = 0; i < 2; ++i) {
    finger_qpos_adr_[i] = m->jnt_qposadr[RequireId(m, mjOBJ_JOINT, kFingerNames[i], "joint")];
    finger_actuator_[i] = RequireId(m, mjOBJ_ACTUATOR, kFingerNames[i], "actuator");
  }
  grip_site_ = RequireId(m, mjOBJ_SITE, "ur5_grip", "site");
  gripper_body_ = RequireId(m, mjOBJ_BODY, "ur5_gripper", "body");
  for (int e = 0; e < m->neq; ++e) {
    const char* name = mj_id2name(m, mjOBJ_EQUALITY, e);
    if (m->eq_type[e] == mjEQ_WELD && name != nullptr &&
        std::string(name).rfind(kGraspPrefix, 0) == 0) {
      if (m->eq_obj1id[e] != gripper_body_) {
        throw UserError(std::string("weld '") + name + "' must have body1=\"ur5_gripper\"");
      }
      grasp_welds_.push_back(e);
    }
  }
  Reset(kHome);
}

void Ur5Arm::Reset(const Ur5Joints& q) {
  mjModel* m = scene_->mutable_model();
  mjData* d = scene_->data();
  for (int i = 0; i < kJoints; ++i) {
    d->qpos[qpos_adr_[i]] = q[i];
    d->qvel[dof_adr_[i]] = 0.0;
  }
  for (int i = 0; i < 2; ++i) d->qpos[finger_qpos_adr_[i]] = kFingerOpen_m;
  finger_setpoint_ = kFingerOpen_m;
  for (int e : grasp_welds_) m->eq_active[e] = 0;
  command_ = {};
  setpoint_ = q;
  gripper_closed_ = false;
  closing_left_s_ = 0.0;
  held_object_ = -1;
  mj_forward(m, d);
}

void Ur5Arm::ShowPose(const Ur5Joints& q, double gripper_opening) {
  Reset(q);
  const double opening = std::isfinite(gripper_opening) ? Clamp(gripper_opening, 0.0, 1.0) : 1.0;
  for (int i = 0; i < 2; ++i) scene_->data()->qpos[finger_qpos_adr_[i]] = opening * kFingerOpen_m;
  finger_setpoint_ = opening * kFingerOpen_m;
  mj_forward(scene_->model(), scene_->data());
}

Ur5Joints Ur5Arm::JointPositions() const {
  Ur5Joints q;
  for (int i = 0; i < kJoints; ++i) q[i] = scene_->data()->qpos[qpos_adr_[i]];
  return q;
}

Ur5Joints Ur5Arm::JointVelocities() const {
  Ur5Joints qd;
  for (int i = 0; i < kJoints; ++i) qd[i] = scene_->data()->qvel[dof_adr_[i]];
  return qd;
}

double Ur5Arm::GripperOpening() const {
  const mjData* d = scene_->data();
  return Clamp(0.5 * (d->qpos[finger_qpos_adr_[0]] + d->qpos[finger_qpos_adr_[1]]) / kFingerOpen_m,
               0.0, 1.0);
}

Eigen::Vector3d Ur5Arm::GripPosition() const {
  const mjtNum* p = scene_->data()->site_xpos + 3 * grip_site_;
  return {p[0], p[1], p[2]};
}

std::vector<std::string> Ur5Arm::GraspableObjects() const {
  std::vector<std::string> names;
  const mjModel* m = scene_->model();
  for (int e : grasp_welds_) names.emplace_back(mj_id2name(m, mjOBJ_BODY, m->eq_obj2id[e]));
  return names;
}

void Ur5Arm::CommandJointVelocities(const Ur5Joints& qd) {
  for (int i = 0; i < kJoints; ++i) {
    command_[i] =
        std::isfinite(qd[i]) ? Clamp(qd[i], -kMaxJointSpeed_rad_s, kMaxJointSpeed_rad_s) : 0.0;
  }
}

void Ur5Arm::CommandGripper(bool close) {
  if (close == gripper_closed_) return;
  gripper_closed_ = close;
  closing_left_s_ = close ? kFingerClosingTime_s : 0.0;
  UpdateGrasp();
}

int Ur5Arm::FindGraspable() const {
  const mjModel* m = scene_->model();
  int best = -1;
  double best_distance = kGraspReach_m;
  for (int e : grasp_welds_) {
    const int object = m->eq_obj2id[e];
    const std::optional<double> distance = GraspOffset(object);
    if (distance && *distance < best_distance) {
      best_distance = *distance;
      best = e;
    }
  }
  return best;
}

std::optional<double> Ur5Arm::GraspOffset(int object) const {
  const mjData* d = scene_->data();
  // The gripper's axes in the world: x closes the fingers, y runs along their faces, z points out
  // of the tool (down, toward the table, when it points down).
  const mjtNum* rg = d->site_xmat + 9 * grip_site_;
  const Eigen::Vector3d axis[3] = {
      {rg[0], rg[3], rg[6]}, {rg[1], rg[4], rg[7]}, {rg[2], rg[5], rg[8]}};
  const mjtNum* p = d->xpos + 3 * object;
  const Eigen::Vector3d offset = Eigen::Vector3d(p[0], p[1], p[2]) - GripPosition();
  const double half[3] = {HalfExtent(*scene_, object, axis[0]),
                          HalfExtent(*scene_, object, axis[1]),
                          HalfExtent(*scene_, object, axis[2])};
  const double along_closing = axis[0].dot(offset), along_faces = axis[1].dot(offset);
  const double along_tool = axis[2].dot(offset);
  // A parallel gripper centres what it closes on, as long as it starts between the open fingers.
  if (std::abs(along_closing) > kFingerInnerHalfOpening_m - half[0]) return std::nullopt;
  // The finger pads must land on it, not beside it.
  if (std::abs(along_faces) > half[1] - kFingerHalfWidth_m) return std::nullopt;
  // The pads reach from the tips (the grip point) kFingerPadLength_m back toward the flange
  // (-z): the object's extent along z must overlap them by kMinPadOverlap_m (a thin slice is
  // only held when the tips come down close to the table).
  const double overlap =
      std::min(0.0, along_tool + half[2]) - std::max(-kFingerPadLength_m, along_tool - half[2]);
  if (overlap < std::min(kMinPadOverlap_m, 2 * half[2])) return std::nullopt;
  return offset.norm();
}

std::optional<Ur5Arm::GraspAlignment> Ur5Arm::AlignmentWith(const std::string& object) const {
  const int body = mj_name2id(scene_->model(), mjOBJ_BODY, object.c_str());
  if (body < 0) return std::nullopt;
  const mjData* d = scene_->data();
  const mjtNum* rg = d->site_xmat + 9 * grip_site_;
  const Eigen::Vector3d closing(rg[0], rg[3], rg[6]), faces(rg[1], rg[4], rg[7]);
  const mjtNum* p = d->xpos + 3 * body;
  const Eigen::Vector3d offset = Eigen::Vector3d(p[0], p[1], p[2]) - GripPosition();
  GraspAlignment a;
  a.closing_axis = closing;
  a.along_closing_m = closing.dot(offset);
  a.along_faces_m = faces.dot(offset);
  // The same window as GraspOffset's.
  a.closing_window_m =
      std::max(0.0, kFingerInnerHalfOpening_m - HalfExtent(*scene_, body, closing));
  a.faces_window_m = std::max(0.0, HalfExtent(*scene_, body, faces) - kFingerHalfWidth_m);
  return a;
}

std::optional<double> Ur5Arm::HighestGraspHeight(const std::string& object) const {
  const int body = mj_name2id(scene_->model(), mjOBJ_BODY, object.c_str());
  if (body < 0) return std::nullopt;
  // With the tool pointing down, the pads run from the tips up: the tips may be at most this far
  // below the object's top and still have kMinPadOverlap_m of it between the pads (GraspOffset).
  const double half = HalfExtent(*scene_, body, Eigen::Vector3d::UnitZ());
  const double top = scene_->data()->xpos[3 * body + 2] + half;
  return top - std::min(kMinPadOverlap_m, 2 * half);
}

void Ur5Arm::UpdateGrasp() {
  mjModel* m = scene_->mutable_model();
  mjData* d = scene_->data();
  if (!gripper_closed_) {
    for (int e : grasp_welds_) m->eq_active[e] = 0;
    held_object_ = -1;
    return;
  }
  finger_closed_target_ = 0.0;
  const int weld = FindGraspable();
  if (weld < 0) return;  // closed on nothing
  const int object = m->eq_obj2id[weld];
  // Hold the object where it is now: relpose = object pose in the gripper frame.
  mjtNum gripper_inverse_pos[3], gripper_inverse_quat[4], rel_pos[3], rel_quat[4];
  mju_negPose(gripper_inverse_pos, gripper_inverse_quat, d->xpos + 3 * gripper_body_,
              d->xquat + 4 * gripper_body_);
  mju_mulPose(rel_pos, rel_quat, gripper_inverse_pos, gripper_inverse_quat, d->xpos + 3 * object,
              d->xquat + 4 * object);
  mjtNum* data = m->eq_data + mjNEQDATA * weld;
  // MuJoCo 2.2 weld data: anchor (3), relative pose (position 3, quaternion 4), torque scale.
  mju_zero3(data);
  mju_copy3(data + 3, rel_pos);
  mju_copy4(data + 6, rel_quat);
  m->eq_active[weld] = 1;
  held_object_ = object;
  // Close the fingers onto the object's narrowest horizontal half-extent.
  double half_width = 0.0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != object) continue;
    const mjtNum* size = m->geom_size + 3 * g;
    const double extent = m->geom_type[g] == mjGEOM_BOX ? std::min(size[0], size[1]) : size[0];
    half_width = std::max(half_width, extent);
  }
  finger_closed_target_ = Clamp(half_width - kFingerInnerOffset_m, 0.0, kFingerOpen_m);
}

void Ur5Arm::Step(double duration_s) {
  const mjModel* m = scene_->model();
  mjData* d = scene_->data();
  const int substeps = std::max(1, static_cast<int>(std::lround(duration_s / m->opt.timestep)));
  for (int s = 0; s < substeps; ++s) {
    for (int i = 0; i < kJoints; ++i) {
      const double q = d->qpos[qpos_adr_[i]];
      const int joint = m->dof_jntid[dof_adr_[i]];
      double target = setpoint_[i] + command_[i] * m->opt.timestep;
      target = Clamp(target, q - kMaxSetpointLead_rad, q + kMaxSetpointLead_rad);
      target = Clamp(target, m->jnt_range[2 * joint], m->jnt_range[2 * joint + 1]);
      setpoint_[i] = target;
      d->ctrl[actuator_[i]] = target;
      // Gravity and Coriolis compensation, as UR's controller provides (last step's bias).
      d->qfrc_applied[dof_adr_[i]] = d->qfrc_bias[dof_adr_[i]];
    }
    // The fingers' set-point travels at the gripper's speed, so the opening (part of x) shows a
    // closing gripper closing rather than a jump.
    const double finger = gripper_closed_ ? finger_closed_target_ : kFingerOpen_m;
    const double travel = kFingerSpeed_m_s * m->opt.timestep;
    finger_setpoint_ = Clamp(finger, finger_setpoint_ - travel, finger_setpoint_ + travel);
    for (int a : finger_actuator_) d->ctrl[a] = finger_setpoint_;
    mj_step(m, d);
    if (closing_left_s_ > 0) {
      closing_left_s_ -= m->opt.timestep;
      if (held_object_ < 0) UpdateGrasp();
    }
  }
}

std::optional<Ur5Joints> Ur5Arm::SolveGraspIk(const Eigen::Vector3d& target, double yaw_rad,
                                              const Ur5Joints& seed) const {
  const mjModel* m = scene_->model();
  mjData* d = ik_data_.get();
  mju_copy(d->qpos, scene_->data()->qpos, m->nq);
  // Desired grip frame: x along the closing axis at yaw, z straight down.
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  Eigen::Matrix3d desired;
  desired << c, s, 0, s, -c, 0, 0, 0, -1;
  mjtNum desired_mat[9], desired_quat[4];
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col) desired_mat[3 * r + col] = desired(r, col);
  mju_mat2Quat(desired_quat, desired_mat);

  const int nv = m->nv;
  std::vector<mjtNum> jacp(3 * nv), jacr(3 * nv);
  constexpr double kLambda = 0.02, kTolerance_m = 1e-3, kOrientationWeight = 0.3;
  for (const Ur5Joints& start : {seed, kHome}) {
    Ur5Joints q = start;
    for (int iteration = 0; iteration < 300; ++iteration) {
      for (int i = 0; i < kJoints; ++i) d->qpos[qpos_adr_[i]] = q[i];
      mj_kinematics(m, d);
      mj_comPos(m, d);
      const mjtNum* p = d->site_xpos + 3 * grip_site_;
      Eigen::Matrix<double, 6, 1> error;
      error.head<3>() = target - Eigen::Vector3d(p[0], p[1], p[2]);
      mjtNum current_quat[4], local_rotation[3], world_rotation[3];
      mju_mat2Quat(current_quat, d->site_xmat + 9 * grip_site_);
      mju_subQuat(local_rotation, desired_quat, current_quat);
      mju_rotVecMat(world_rotation, local_rotation, d->site_xmat + 9 * grip_site_);
      for (int k = 0; k < 3; ++k) error[3 + k] = kOrientationWeight * world_rotation[k];
      if (error.head<3>().norm() < kTolerance_m &&
          error.tail<3>().norm() < 0.01 * kOrientationWeight) {
        return q;
      }
      mj_jacSite(m, d, jacp.data(), jacr.data(), grip_site_);
      Eigen::Matrix<double, 6, kJoints> jacobian;
      for (int i = 0; i < kJoints; ++i) {
        for (int k = 0; k < 3; ++k) {
          jacobian(k, i) = jacp[k * nv + dof_adr_[i]];
          jacobian(3 + k, i) = kOrientationWeight * jacr[k * nv + dof_adr_[i]];
        }
      }
      const Eigen::Matrix<double, 6, 6> jjt =
          jacobian * jacobian.transpose() +
          kLambda * kLambda * Eigen::Matrix<double, 6, 6>::Identity();
      const Eigen::Matrix<double, kJoints, 1> dq = jacobian.transpose() * jjt.ldlt().solve(error);
      for (int i = 0; i < kJoints; ++i) {
        const int joint = m->dof_jntid[dof_adr_[i]];
        q[i] = Clamp(q[i] + Clamp(dq[i], -0.3, 0.3), m->jnt_range[2 * joint],
                     m->jnt_range[2 * joint + 1]);
      }
    }
  }
  return std::nullopt;
}

}  // namespace recon::worlds
