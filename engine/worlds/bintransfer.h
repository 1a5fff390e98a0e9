#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/rng.h"
#include "engine/worlds/guarded_ur5.h"
#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/ur5_arm.h"
#include "engine/worlds/world.h"

namespace recon::worlds {

/// The paper's Robosuite bin-transfer task (REFERENCE.md section 3) in the simulated UR5 cell
/// (assets/mjcf/bintransfer.xml): four objects lie at random in the left bin; the robot picks up
/// the right-most one and puts it into the right bin.
///
/// "Left" and "right" are as a viewer facing the robot sees them, as in the paper's figure
/// (Robosuite's front view): the left bin is at -y, the right bin at +y (the arm faces +x). The
/// target ("right-most") object is the one nearest the right bin: the largest coordinate along
/// the left-bin -> right-bin axis (the largest y) once the dropped objects have settled.
///
/// x = 6 joint angles (rad); y = the four objects' x, y, z (m) in ObjectNames() order (12);
/// b = the target's x, y, z ("position", RECON-P, d = 3), its distance from the grip point
/// ("distance", RECON-D, d = 1) or nothing ("none"); u = 6 joint velocities (rad/s), applied for
/// one 0.1 s control period (the paper's 10 Hz).
///
/// The gripper is scripted by the world, because the paper's u holds joint velocities only: it
/// closes when the grip point comes within kGraspRadius_m of the target's centre (never near
/// another object), and opens, for good, when the held target's centre is over the right bin (at
/// least kWallClearance_m inside its walls) at or below kReleaseHeight_m; the target then drops
/// about 10 cm into the bin. The conditions are checked every kGripperCheckPeriod_s inside a step,
/// so a moving arm cannot skip past them.
///
/// The expert steps in joint space toward IK solutions of five waypoints (above the target, at
/// it, back above it, above the right bin, down to the release height), each joint velocity a
/// proportional step clamped to kExpertMaxSpeed_rad_s; it commands zero once the target is
/// released. It succeeds in 200 of 200 seeded layouts (tests/worlds/bintransfer_test.cc).
class BinTransfer : public World {
 public:
  static constexpr int kNumObjects = 4;
  static constexpr double kControlPeriod_s = 0.1;
  /// 6 s: the expert finishes in 43 steps on average and at most 46 (seeds 0-199), which leaves
  /// a learned policy some slack.
  static constexpr int kEpisodeLength = 60;
  static constexpr int kPlayPerScenario = 3;

  // The cell, as in assets/mjcf/bintransfer.xml (the constructor checks the bin centres).
  static constexpr double kLeftBinX_m = 0.5, kLeftBinY_m = -0.2;
  static constexpr double kRightBinX_m = 0.5, kRightBinY_m = 0.2;
  static constexpr double kBinInnerHalfWidth_m = 0.11;
  static constexpr double kBinFloorTop_m = 0.0;
  static constexpr double kBinWallTop_m = 0.075;

  /// Object centres are drawn at least this far from the bin's inner walls...
  static constexpr double kWallClearance_m = 0.035;
  /// ...and at least this far apart: the open fingers reach 6 cm from the grip point and the
  /// widest object 3 cm from its centre, so grasping one never touches another.
  static constexpr double kMinSeparation_m = 0.09;

  /// The gripper closes when the grip point is this close to the target's centre.
  static constexpr double kGraspRadius_m = 0.015;
  /// The held target is released once its centre is at or below this height over the right bin.
  static constexpr double kReleaseHeight_m = 0.13;
  static constexpr double kGripperCheckPeriod_s = 0.02;

  /// The expert's waypoint heights (grip point, m) and its joint-space controller.
  static constexpr double kCarryHeight_m = 0.2;
  static constexpr double kReleaseGripHeight_m = 0.11;
  static constexpr double kWaypointTolerance_m = 0.015;
  static constexpr double kExpertGain_per_s = 3.0;
  static constexpr double kExpertMaxSpeed_rad_s = 0.8;

  /// Object centres in the plane, in ObjectNames() order: a layout a test or tool may impose.
  using Layout = std::array<Eigen::Vector2d, kNumObjects>;

  /// Throws UserError for an unknown placement or a negative or non-finite sigma (metres).
  BinTransfer(const std::string& placement, double noise_sigma);
  BinTransfer(const BinTransfer&) = delete;
  BinTransfer& operator=(const BinTransfer&) = delete;

  std::string Name() const override { return "bintransfer"; }
  DataSpec Spec() const override;
  int EpisodeLength() const override { return kEpisodeLength; }
  /// Arm at Ur5Arm::kHome, objects dropped at a random layout in the left bin and settled.
  /// UserError naming the target's position if the expert's IK cannot reach it.
  void Reset(uint64_t seed) override;
  Observation Observe() const override;
  void Step(const std::vector<float>& u) override;
  std::vector<float> ExpertAction() const override;
  std::vector<float> BeaconReading() override;
  /// A fresh random layout (settled in a scratch copy of the scene) seen with the arm where it is
  /// now; the scenario is not changed.
  PlaySample SamplePlay() override;
  int PlaySamplesPerScenario() const override { return kPlayPerScenario; }
  /// Distance from the target's centre to the right bin's centre in the plane, metres: the score
  /// of a rollout. Experiments instead score actions along the expert's demonstrations (the
  /// paper's metric, ScoresActions()), which MetricName describes.
  double EpisodeMetric() const override;
  /// Action MSE against the expert, lower is better; success; 10 Hz.
  WorldTraits Traits() const override;
  /// The target is released and lies inside the right bin (centre within its inner footprint,
  /// below its wall top).
  bool TaskSucceeded() const override;

  /// Like Reset(seed) but with the objects dropped at `layout` instead of a random one (the seed
  /// still drives the beacon noise and play data). For tests and tools; the layout is not checked.
  void ResetToLayout(uint64_t seed, const Layout& layout);

  static const std::vector<std::string>& Placements();
  /// Beacon size d of a placement (throws UserError for an unknown one).
  static int BeaconDim(const std::string& placement);
  /// Body names of the objects, in the order y lists them.
  static const std::array<const char*, kNumObjects>& ObjectNames();
  /// Draws a layout in the left bin by rejection sampling (see kMinSeparation_m).
  static Layout DrawLayout(Rng& rng);

  /// Index (ObjectNames() order) of the target object in this scenario.
  int TargetIndex() const { return target_; }
  Eigen::Vector3d ObjectPosition(int index) const;
  Eigen::Vector3d GripPosition() const { return arm_->GripPosition(); }
  bool TargetHeld() const;
  bool TargetReleased() const { return released_; }
  /// Steps taken since Reset.
  int Steps() const { return steps_; }
  MujocoModel& scene() { return scene_; }
  Ur5Arm& arm() { return *arm_; }

  /// What the safety envelope did to this world's commands since it was made.
  safety::SafetyStats safety_stats() const { return guarded_->guard().stats(); }
  /// The UR5 as a cell holds it (Tabletop::guarded_arm).
  safety::GuardedArm& guarded_arm() { return guarded_->guard(); }

 private:
  enum class Phase { kApproach, kDescend, kLift, kTransfer, kLower, kDone };

  // Drops the objects at `layout` into `scene` (arm at `q`) and lets them settle.
  void DropObjects(MujocoModel& scene, Ur5Arm& arm, const Layout& layout, const Ur5Joints& q);
  void PlanExpert();
  // IK for a grip position with the fingers' yaw chosen to keep wrist 3 at its home angle.
  std::optional<Ur5Joints> SolveWaypoint(const Eigen::Vector3d& grip, const Ur5Joints& seed) const;
  void UpdateGripper();
  void UpdatePhase();
  std::vector<float> Beacon(const Eigen::Vector3d& target, const Eigen::Vector3d& grip,
                            Rng& rng) const;

  std::string placement_;
  double noise_sigma_;
  MujocoModel scene_;
  std::unique_ptr<Ur5Arm> arm_;
  // Every velocity command passes the guarded arm (the default envelope). The gripper is the
  // world's own grasp detector's, not a command, so it goes to the arm directly.
  std::unique_ptr<GuardedUr5> guarded_;
  // The scratch scene play layouts settle in, made on first use.
  std::unique_ptr<MujocoModel> play_scene_;
  std::unique_ptr<Ur5Arm> play_arm_;
  std::array<int, kNumObjects> object_body_{}, object_qpos_{};
  std::array<double, kNumObjects> object_half_height_m_{};
  // The fingers' yaw and the grip point's bearing from the base at Ur5Arm::kHome.
  double home_yaw_rad_ = 0.0;
  double home_bearing_rad_ = 0.0;

  int target_ = 0;
  bool released_ = false;
  int steps_ = 0;
  Phase phase_ = Phase::kApproach;
  Eigen::Vector3d above_target_, above_bin_;
  Ur5Joints q_above_target_{}, q_grasp_{}, q_above_bin_{}, q_release_{};
  // Separate streams so that drawing play samples never changes a demonstration's beacon noise.
  Rng noise_rng_{0};
  Rng play_rng_{0};
};

/// Builds a BinTransfer world; throws UserError listing the valid names for an unknown placement.
std::unique_ptr<World> MakeBinTransfer(const std::string& placement, double noise_sigma);

/// Valid beacon placements of the bin-transfer world: none, position, distance.
const std::vector<std::string>& BinTransferPlacements();

}  // namespace recon::worlds
