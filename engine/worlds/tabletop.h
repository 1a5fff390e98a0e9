#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/image.h"
#include "engine/core/rng.h"
#include "engine/worlds/guarded_ur5.h"
#include "engine/worlds/mujoco_model.h"
#include "engine/worlds/scene_renderer.h"
#include "engine/worlds/ur5_arm.h"
#include "engine/worlds/world.h"

namespace recon::worlds {

/// What the gripper does with the toast, as a teacher's readout says it.
enum class ToastGrip {
  kOpen,             ///< the gripper is open
  kClosing,          ///< the fingers are on their way in, nothing held yet
  kHolding,          ///< the toast is in the gripper
  kClosedOnNothing,  ///< the fingers shut without the toast between them
};

/// How a Tabletop world is configured.
struct TabletopOptions {
  /// "none" (the Baseline, d = 0) or "plate" (the beacon beside the plate: its x, y on the table
  /// in metres, d = 2).
  std::string placement = "plate";
  /// "paper": the plate at one of two marked places (left or right edge), the bowl anywhere
  /// else, demonstrations two per configuration (the paper's protocol). "wide": the plate
  /// anywhere in a band along either edge, one demonstration per scenario (harder).
  std::string layout = "paper";
  /// Standard deviation of Gaussian noise on each beacon coordinate, metres. A DWM1001 is good to
  /// about 10 cm (REFERENCE.md section 4); kDwm1001NoiseSigma_m is what the simulated one has.
  double noise_sigma_m = 0.0;
  /// "image" (the camera, the paper's y) or "state": y is the true table positions of the toast,
  /// the plate and the bowl (x, y of each, metres): the privileged diagnostic that separates what
  /// a learner loses to vision from what it loses to control. No renderer is needed for "state".
  std::string observation = "image";
  /// Camera image size; the paper's policy saw small images, 64 x 64 by default.
  int image_width = 64;
  int image_height = 64;
};

/// The paper's real-robot task in the simulated cell (assets/mjcf/tabletop.xml): pick up the
/// toast and drop it on the blue plate, which is at the left or the right edge of the table, while
/// a red bowl stands anywhere. The robot sees its joints and the top-down camera image; the beacon
/// beside the plate is there only while teaching.
///
/// x = 6 joint angles and the gripper opening (7); y = the camera image, channels first, values
/// 0-255 (3 x H x W); b = the plate beacon's table position (2); u = 6 joint velocities (rad/s)
/// and a gripper command (close when > 0.5) (7). Steps are 0.1 s (the paper's 10 Hz). A recorded
/// demonstration stops when the toast is on the plate (about 140 steps; the paper's had about
/// 150 samples); a rollout runs 200 steps.
class Tabletop : public World {
 public:
  static constexpr int kEpisodeLength = 200;
  static constexpr double kControlPeriod_s = 0.1;
  /// The paper recorded 4 s of play data at 10 Hz (40 (y, b) pairs) for 4 demonstrations: 10 per
  /// demonstration scenario.
  static constexpr int kPlayPerScenario = 10;
  static constexpr double kPlateRadius_m = 0.09;
  /// Where a scene may put the bowl (table frame, metres): the widest of the objects' ranges.
  static constexpr double kBowlMinX = 0.22, kBowlMaxX = 0.82, kBowlMaxAbsY = 0.5;
  /// The bowl's and the toast's footprints (assets/mjcf/tabletop.xml: a 7 cm cylinder, a 10 cm
  /// square slice).
  static constexpr double kBowlRadius_m = 0.07, kToastRadius_m = 0.05;
  /// Per-axis position noise of a DWM1001's location engine, as the simulated one has it
  /// (devices/uwb/simulated_dwm1001.h) and the cell's calibration measures it: the default beacon
  /// noise of a simulated tabletop session or experiment.
  static constexpr double kDwm1001NoiseSigma_m = 0.07;

  /// Throws UserError for an unknown placement, bad noise or image size, or a null renderer.
  Tabletop(const TabletopOptions& options, std::unique_ptr<SceneRenderer> renderer);

  std::string Name() const override {
    return options_.observation == "state" ? "tabletop-state" : "tabletop";
  }
  DataSpec Spec() const override;
  int EpisodeLength() const override { return kEpisodeLength; }
  void Reset(uint64_t seed) override;
  /// 2 in the paper layout, 1 in the wide one.
  int DemosPerConfiguration() const override;
  int SuggestedDemos() const override;
  /// Paper layout: configuration c has the plate on the left (c even) or the right (c odd) at
  /// its marked place, and the bowl where `configuration_seed` puts it.
  void ResetTake(uint64_t seed, uint64_t configuration_seed, int configuration) override;
  /// The six joint velocities may be perturbed while recording, the gripper command not.
  std::vector<float> ActionNoiseScale() const override;
  Observation Observe() const override;
  void Step(const std::vector<float>& u) override;
  std::vector<float> ExpertAction() const override;
  std::vector<float> BeaconReading() override;
  PlaySample SamplePlay() override;
  int PlaySamplesPerScenario() const override { return kPlayPerScenario; }
  /// Final distance from the toast to the plate centre in the table plane, metres.
  double EpisodeMetric() const override;
  /// The toast is on the plate and the arm has risen back above it: a teacher stops there.
  bool DemonstrationDone() const override;
  /// The toast lies on the plate, released, the gripper is open and its finger tips are
  /// kClearOfToast_m above the toast's top or beside it: a person's take ends here.
  bool GoalHoldsAndClear() const override;
  /// How far the open gripper must be from a delivered toast for a person's take to end.
  static constexpr double kClearOfToast_m = 0.03;
  /// The toast's final distance to the plate, lower is better; success; 10 Hz.
  WorldTraits Traits() const override;
  /// The toast lies on the plate, released.
  bool TaskSucceeded() const override;
  /// "toast_moved" (the toast left its pick-up place by more than 3 cm), "toast_held" (still in
  /// the gripper at the end), "grip_nearer_bowl" (the gripper ended nearer the bowl than the
  /// plate: the paper's Baseline failure), "toast_to_bowl_m", "grasped" (the toast was held at
  /// some point), "closest_approach_m" (of the grip point to the toast before a grasp) and
  /// "closes_on_nothing" (the gripper shut without the toast before any grasp), "grasps" (how
  /// often the toast was picked up: 2 or more is a regrasp), "toast_off_table" (it fell below
  /// the table's top) and "toast_to_plate_m".
  std::map<std::string, double> OutcomeDetails() const override;
  /// The plate, the bowl and the toast.
  std::map<std::string, std::array<double, 2>> ObjectLayout() const override;
  /// The pose the current camera image shows, valid after Reset and Step: MuJoCo's qpos (arm
  /// joints, fingers, the toast's free joint) as the frame was rendered from it, then the mocap
  /// bodies' (plate with its beacon, bowl) positions (3 each) and quaternions (4 each).
  /// ReplayStateSize() values.
  std::vector<double> ReplayState() const override;
  /// Sets that pose at rest, recomputes positions and renders CameraImage() again.
  void ShowReplayState(const std::vector<double>& state) override;
  int ReplayStateSize() const;
  /// The table where the scenes put the bowl (the widest of the objects' ranges), and the
  /// plate's, the bowl's and the toast's footprints (tabletop_probe.cc).
  std::optional<ObjectArea> PlaceableArea() const override;
  /// The plate (with its beacon), the bowl or the toast, moved in the table's plane at its
  /// height; the camera image is drawn again.
  void PlaceObject(const std::string& object, const std::array<double, 2>& xy) override;
  bool TaskFeasible() const override;

  static const std::vector<std::string>& Placements();
  static const std::vector<std::string>& Layouts();
  const std::string& layout() const { return options_.layout; }

  /// Like Reset(seed) but with the plate and the bowl where given (table frame, metres), for
  /// tests and tools; the seed still drives beacon noise and play data. UserError if the layout
  /// puts the expert's waypoints out of the arm's reach.
  void ResetToLayout(uint64_t seed, const Eigen::Vector3d& plate, const Eigen::Vector3d& bowl);

  /// The last camera image (rendered after every Reset and Step).
  const RgbImage& CameraImage() const { return image_; }
  Eigen::Vector3d ToastPosition() const;
  Eigen::Vector3d PlatePosition() const;
  Eigen::Vector3d BowlPosition() const;
  Eigen::Vector3d BeaconPosition() const;
  /// Which edge the plate is at in this scenario: +1 left (+y), -1 right.
  int PlateSide() const { return plate_side_; }
  /// Distance from the toast to the bowl centre in the plane (a Baseline failure goes there).
  double ToastToBowlDistance() const;
  MujocoModel& scene() { return scene_; }
  Ur5Arm& arm() { return *arm_; }
  const Ur5Arm& arm() const { return *arm_; }

  /// What the gripper does with the toast now.
  ToastGrip GripOnToast() const;
  /// The top of what lies straight under the grip point (the toast, the plate, the table...),
  /// the arm and a held toast left out: where a teacher's drop line from the gripper lands, so
  /// a spot drawn there lies on what the gripper would come down onto.
  Eigen::Vector3d SurfaceBelowGrip() const;
  /// The grip point's heights above the table at which closing the gripper over the toast holds
  /// it: from the safety envelope's tool floor (the lowest the tips go) to where the finger pads
  /// still reach the slice's side (Ur5Arm::HighestGraspHeight).
  std::pair<double, double> GraspHeights() const;

  /// The envelope this world's commands pass (the tool floor a grasp comes down to).
  const safety::SafetyLimits& safety_limits() const {
    return guarded_->guard().envelope().limits();
  }
  /// What the safety envelope did to this world's commands since it was made.
  safety::SafetyStats safety_stats() const { return guarded_->guard().stats(); }
  /// The UR5 as a cell holds it (a devices::Arm behind the envelope, watchdog and e-stop),
  /// which every Step commands: engage its e-stop and the arm stops, whoever drives it.
  safety::GuardedArm& guarded_arm() { return guarded_->guard(); }
  /// The world's simulated time: kControlPeriod_s a period.
  const devices::ManualClock& clock() const { return guarded_->clock(); }
  /// One control period under the command in force, as Step runs it after commanding: the
  /// watchdogs, the physics, the camera, the clock. For a cell driven through guarded_arm().
  void Advance();

 private:
  void PlaceMocap(int body, const Eigen::Vector3d& position);
  Eigen::Vector3d DrawBowlPosition(Rng& rng) const;
  /// The plate's place on side `side` (+1 left, -1 right) under the configured layout.
  Eigen::Vector3d DrawPlatePosition(int side, Rng& rng) const;
  /// The toast at its pick-up place and the arm at home (drawn from rng_ after the plate).
  void PlaceToastAndArm();
  /// After the plate and bowl are placed: positions, the reachability check, the first frame.
  void FinishReset();
  void Render();
  /// Follows the approach to the toast for OutcomeDetails: the closest the grip point came before
  /// a grasp, and how often the gripper closed on nothing.
  void TrackGrasp(bool was_closed);
  /// Advance() with the gripper's state before this period's command.
  void AdvanceFrom(bool was_closed);
  /// UserError if the expert's waypoints of this layout are out of the arm's reach.
  void CheckReachable() const;
  std::vector<float> ImageAsY() const;

  TabletopOptions options_;
  std::unique_ptr<SceneRenderer> renderer_;
  MujocoModel scene_;
  std::unique_ptr<Ur5Arm> arm_;
  // Every command, the expert's, a teacher's or a policy's, passes the guarded arm.
  std::unique_ptr<GuardedUr5> guarded_;
  Rng rng_{0};
  int plate_body_ = -1, bowl_body_ = -1, toast_body_ = -1, beacon_site_ = -1;
  int toast_qpos_ = -1;
  int plate_side_ = 1;
  RgbImage image_;
  bool grasped_ = false;
  double closest_approach_m_ = 0.0;
  int closes_on_nothing_ = 0;
  int grasps_ = 0;              ///< times the toast went from free to held
  bool holding_toast_ = false;  ///< at the last period's end
};

}  // namespace recon::worlds
