#include "engine/worlds/bintransfer.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "engine/core/error.h"
#include "engine/core/strings.h"
#include "engine/worlds/scenario_streams.h"
#include "engine/worlds/scene_assets.h"

namespace recon::worlds {
namespace {

constexpr char kScene[] = "bintransfer";
// Objects are dropped from just above their resting height and given this long to settle.
constexpr double kDropGap_m = 0.002;
constexpr double kSettle_s = 0.15;
constexpr int kMaxLayoutAttempts = 1000;
constexpr int kMaxPlacementTries = 100;

Eigen::Vector3d BodyPosition(const MujocoModel& scene, int body) {
  const mjtNum* p = scene.data()->xpos + 3 * body;
  return {p[0], p[1], p[2]};
}

// Where a point lies along the left-bin -> right-bin axis: larger is nearer the right bin.
double AlongBinAxis(const Eigen::Vector3d& p) {
  const Eigen::Vector2d axis = Eigen::Vector2d(BinTransfer::kRightBinX_m - BinTransfer::kLeftBinX_m,
                                               BinTransfer::kRightBinY_m - BinTransfer::kLeftBinY_m)
                                   .normalized();
  return axis.dot(p.head<2>());
}

int RightMost(const std::array<Eigen::Vector3d, BinTransfer::kNumObjects>& positions) {
  int best = 0;
  for (int i = 1; i < BinTransfer::kNumObjects; ++i) {
    if (AlongBinAxis(positions[i]) > AlongBinAxis(positions[best])) best = i;
  }
  return best;
}

// Yaw of the grip site's x axis (the fingers' closing axis) about the vertical.
double GripYaw(const MujocoModel& scene) {
  const int site = mj_name2id(scene.model(), mjOBJ_SITE, "ur5_grip");
  const mjtNum* r = scene.data()->site_xmat + 9 * site;
  return std::atan2(r[3], r[0]);
}

void CheckBinPosition(const mjModel* m, const char* name, double x_m, double y_m) {
  const int body = mj_name2id(m, mjOBJ_BODY, name);
  if (body < 0 || std::abs(m->body_pos[3 * body] - x_m) > 1e-9 ||
      std::abs(m->body_pos[3 * body + 1] - y_m) > 1e-9) {
    throw std::logic_error(std::string("assets/mjcf/bintransfer.xml: body ") + name +
                           " must sit where BinTransfer's constants say");
  }
}

}  // namespace

const std::vector<std::string>& BinTransfer::Placements() {
  static const std::vector<std::string> kPlacements = {"none", "position", "distance"};
  return kPlacements;
}

int BinTransfer::BeaconDim(const std::string& placement) {
  if (placement == "none") return 0;
  if (placement == "position") return 3;
  if (placement == "distance") return 1;
  throw UserError("unknown beacon placement '" + placement +
                  "' for bintransfer; valid placements: " + JoinNames(Placements()));
}

const std::array<const char*, BinTransfer::kNumObjects>& BinTransfer::ObjectNames() {
  static const std::array<const char*, kNumObjects> kNames = {"red_box", "green_cylinder",
                                                              "blue_box", "yellow_cylinder"};
  return kNames;
}

BinTransfer::BinTransfer(const std::string& placement, double noise_sigma)
    : placement_(placement), noise_sigma_(noise_sigma), scene_(LoadScene(kScene)) {
  BeaconDim(placement_);  // validates the name
  if (!std::isfinite(noise_sigma_) || noise_sigma_ < 0.0) {
    std::ostringstream msg;
    msg << "beacon noise sigma must be a finite number of metres >= 0, got " << noise_sigma_;
    throw UserError(msg.str());
  }
  const mjModel* m = scene_.model();
  CheckBinPosition(m, "left_bin", kLeftBinX_m, kLeftBinY_m);
  CheckBinPosition(m, "right_bin", kRightBinX_m, kRightBinY_m);
  for (int i = 0; i < kNumObjects; ++i) {
    const int body = mj_name2id(m, mjOBJ_BODY, ObjectNames()[i]);
    if (body < 0 || m->body_jntnum[body] != 1 || m->jnt_type[m->body_jntadr[body]] != mjJNT_FREE ||
        m->body_geomnum[body] != 1) {
      throw std::logic_error(std::string("assets/mjcf/bintransfer.xml: object ") +
                             ObjectNames()[i] + " must be a body with a free joint and one geom");
    }
    object_body_[i] = body;
    object_qpos_[i] = m->jnt_qposadr[m->body_jntadr[body]];
    const int geom = m->body_geomadr[body];
    // Boxes and cylinders stand upright: the half-height is the last size of a box, the second of
    // a cylinder.
    object_half_height_m_[i] = m->geom_size[3 * geom + (m->geom_type[geom] == mjGEOM_BOX ? 2 : 1)];
  }
  arm_ = std::make_unique<Ur5Arm>(scene_);  // resets to kHome
  guarded_ = std::make_unique<GuardedUr5>(*arm_, kControlPeriod_s);
  home_yaw_rad_ = GripYaw(scene_);
  home_bearing_rad_ = std::atan2(arm_->GripPosition().y(), arm_->GripPosition().x());

  // The right-bin waypoints do not depend on the layout: solve them once.
  above_bin_ = Eigen::Vector3d(kRightBinX_m, kRightBinY_m, kCarryHeight_m);
  const auto above_bin = SolveWaypoint(above_bin_, Ur5Arm::kHome);
  const auto release =
      above_bin ? SolveWaypoint({kRightBinX_m, kRightBinY_m, kReleaseGripHeight_m}, *above_bin)
                : std::nullopt;
  if (!release) throw std::logic_error("bintransfer: the right bin is out of the UR5's reach");
  q_above_bin_ = *above_bin;
  q_release_ = *release;
  Reset(0);
}

DataSpec BinTransfer::Spec() const {
  DataSpec spec;
  spec.x_dim = Ur5Arm::kJoints;
  spec.y_shape = {3 * kNumObjects};
  spec.b_dim = BeaconDim(placement_);
  spec.u_dim = Ur5Arm::kJoints;
  return spec;
}

BinTransfer::Layout BinTransfer::DrawLayout(Rng& rng) {
  const double half = kBinInnerHalfWidth_m - kWallClearance_m;
  for (int attempt = 0; attempt < kMaxLayoutAttempts; ++attempt) {
    Layout layout;
    int placed = 0;
    for (int tries = 0; placed < kNumObjects && tries < kMaxPlacementTries; ++tries) {
      const Eigen::Vector2d candidate(kLeftBinX_m + rng.Uniform(-half, half),
                                      kLeftBinY_m + rng.Uniform(-half, half));
      bool free = true;
      for (int j = 0; j < placed; ++j) {
        free = free && (candidate - layout[j]).norm() >= kMinSeparation_m;
      }
      if (free) layout[placed++] = candidate;
    }
    // A dead end (the first objects leave no room for the rest) starts the layout over.
    if (placed == kNumObjects) return layout;
  }
  throw std::logic_error("bintransfer: no layout fits the left bin (layout constants are wrong)");
}

void BinTransfer::DropObjects(MujocoModel& scene, Ur5Arm& arm, const Layout& layout,
                              const Ur5Joints& q) {
  const mjModel* m = scene.model();
  mjData* d = scene.data();
  // A full reset (time, warm starts, contacts) so a scenario depends on its seed alone.
  mj_resetData(m, d);
  for (int i = 0; i < kNumObjects; ++i) {
    mjtNum* pose = d->qpos + object_qpos_[i];
    pose[0] = layout[i].x();
    pose[1] = layout[i].y();
    pose[2] = kBinFloorTop_m + object_half_height_m_[i] + kDropGap_m;
    pose[3] = 1.0;
    pose[4] = pose[5] = pose[6] = 0.0;
  }
  arm.Reset(q);  // also runs mj_forward
  arm.Step(kSettle_s);
}

void BinTransfer::Reset(uint64_t seed) {
  Rng rng(Rng::Derive(seed, kScenarioStream));
  ResetToLayout(seed, DrawLayout(rng));
}

void BinTransfer::ResetToLayout(uint64_t seed, const Layout& layout) {
  noise_rng_.Seed(Rng::Derive(seed, kNoiseStream));
  play_rng_.Seed(Rng::Derive(seed, kPlayStream));
  DropObjects(scene_, *arm_, layout, Ur5Arm::kHome);
  guarded_->Placed();
  std::array<Eigen::Vector3d, kNumObjects> positions;
  for (int i = 0; i < kNumObjects; ++i) positions[i] = ObjectPosition(i);
  target_ = RightMost(positions);
  released_ = false;
  steps_ = 0;
  phase_ = Phase::kApproach;
  PlanExpert();
}

Eigen::Vector3d BinTransfer::ObjectPosition(int index) const {
  return BodyPosition(scene_, object_body_.at(index));
}

bool BinTransfer::TargetHeld() const { return arm_->HeldObject() == object_body_[target_]; }

Observation BinTransfer::Observe() const {
  Observation obs;
  for (double q : arm_->JointPositions()) obs.x.push_back(static_cast<float>(q));
  obs.y.reserve(3 * kNumObjects);
  for (int i = 0; i < kNumObjects; ++i) {
    const Eigen::Vector3d p = ObjectPosition(i);
    for (int k = 0; k < 3; ++k) obs.y.push_back(static_cast<float>(p[k]));
  }
  return obs;
}

void BinTransfer::Step(const std::vector<float>& u) {
  if (u.size() != Ur5Arm::kJoints) {
    throw std::invalid_argument("BinTransfer::Step: action must have 6 joint velocities, got " +
                                std::to_string(u.size()));
  }
  Ur5Joints qd;
  for (int i = 0; i < Ur5Arm::kJoints; ++i) qd[i] = u[i];
  guarded_->Command(qd);
  guarded_->BeforePeriod();
  const int checks = static_cast<int>(std::lround(kControlPeriod_s / kGripperCheckPeriod_s));
  for (int c = 0; c < checks; ++c) {
    arm_->Step(kGripperCheckPeriod_s);
    UpdateGripper();
  }
  guarded_->AfterPeriod();
  ++steps_;
  UpdatePhase();
}

void BinTransfer::UpdateGripper() {
  if (released_) return;  // the task is over: never grasp again
  const Eigen::Vector3d target = ObjectPosition(target_);
  if (!arm_->GripperClosed()) {
    if ((arm_->GripPosition() - target).norm() < kGraspRadius_m) arm_->CommandGripper(true);
    return;
  }
  const double inside = kBinInnerHalfWidth_m - kWallClearance_m;
  if (TargetHeld() && std::abs(target.x() - kRightBinX_m) <= inside &&
      std::abs(target.y() - kRightBinY_m) <= inside && target.z() <= kReleaseHeight_m) {
    arm_->CommandGripper(false);
    released_ = true;
  }
}

std::vector<float> BinTransfer::Beacon(const Eigen::Vector3d& target, const Eigen::Vector3d& grip,
                                       Rng& rng) const {
  std::vector<double> clean;
  if (placement_ == "position") clean = {target.x(), target.y(), target.z()};
  if (placement_ == "distance") clean = {(grip - target).norm()};
  std::vector<float> b(clean.size());
  for (size_t i = 0; i < clean.size(); ++i) {
    const double noise = noise_sigma_ > 0.0 ? noise_sigma_ * rng.Normal() : 0.0;
    b[i] = static_cast<float>(clean[i] + noise);
  }
  return b;
}

std::vector<float> BinTransfer::BeaconReading() {
  return Beacon(ObjectPosition(target_), arm_->GripPosition(), noise_rng_);
}

PlaySample BinTransfer::SamplePlay() {
  // The paper's play data randomise the objects without simulating the robot. The new layout
  // settles in a scratch scene, so the scenario (and its physics state) is untouched.
  if (play_scene_ == nullptr) {
    play_scene_ = std::make_unique<MujocoModel>(LoadScene(kScene));
    play_arm_ = std::make_unique<Ur5Arm>(*play_scene_);
  }
  const Ur5Joints q = arm_->JointPositions();
  DropObjects(*play_scene_, *play_arm_, DrawLayout(play_rng_), q);
  std::array<Eigen::Vector3d, kNumObjects> positions;
  PlaySample play;
  for (int i = 0; i < kNumObjects; ++i) {
    positions[i] = BodyPosition(*play_scene_, object_body_[i]);
    for (int k = 0; k < 3; ++k) play.y.push_back(static_cast<float>(positions[i][k]));
  }
  for (double v : q) play.x.push_back(static_cast<float>(v));
  play.b = Beacon(positions[RightMost(positions)], arm_->GripPosition(), play_rng_);
  return play;
}

double BinTransfer::EpisodeMetric() const {
  const Eigen::Vector3d p = ObjectPosition(target_);
  return std::hypot(p.x() - kRightBinX_m, p.y() - kRightBinY_m);
}

WorldTraits BinTransfer::Traits() const {
  WorldTraits traits;
  traits.metric_name = "action MSE against the expert ((rad/s)^2, lower is better)";
  traits.metric_key = "action_mse";
  traits.scores_actions = true;
  traits.has_success = true;
  traits.step_seconds = 0.1;
  return traits;
}

bool BinTransfer::TaskSucceeded() const {
  const Eigen::Vector3d p = ObjectPosition(target_);
  return released_ && !TargetHeld() && std::abs(p.x() - kRightBinX_m) < kBinInnerHalfWidth_m &&
         std::abs(p.y() - kRightBinY_m) < kBinInnerHalfWidth_m && p.z() < kBinWallTop_m;
}

std::unique_ptr<World> MakeBinTransfer(const std::string& placement, double noise_sigma) {
  return std::make_unique<BinTransfer>(placement, noise_sigma);
}

const std::vector<std::string>& BinTransferPlacements() { return BinTransfer::Placements(); }

}  // namespace recon::worlds
