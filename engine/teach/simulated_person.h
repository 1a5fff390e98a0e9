#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <string>

#include "engine/core/rng.h"
#include "engine/teach/cartesian_teleop.h"
#include "engine/worlds/tabletop.h"

namespace recon::teach {

/// How a simulated person teleoperates the tabletop by keyboard. The defaults describe a
/// newcomer at the studio's keys, as a person was measured teaching there: reaction times of
/// 0.2-0.4 s, overshoot and correction, pauses to look, a grasp that closes on nothing now and
/// then, and routes that differ from take to take.
struct PersonStyle {
  /// A held arrow key's speed (the studio's keyboard: 0.1 m/s per axis).
  double speed_m_s = 0.1;
  /// What the person sees lags the arm by this much, drawn per decision (seconds).
  double reaction_min_s = 0.2, reaction_max_s = 0.4;
  /// At each step of the task (reached the toast, grasped, lifted, ...) the person stops to look
  /// with this probability, for a time drawn between the two bounds (seconds).
  double pause_probability = 0.35;
  double pause_min_s = 0.4, pause_max_s = 1.8;
  /// A person lets go of a key a little before the target, expecting the arm to coast: this
  /// share of their own reaction time (0 = no anticipation, 1 = none of the lag overshoots).
  double anticipation = 0.5;
  /// While an arrow is held, the chance per second of letting go for a moment (hesitation).
  double hesitation_per_s = 0.3;
  /// Where the person thinks the toast's middle is, off by a Gaussian error per table axis
  /// (metres): y is the depth of the studio's first view (from the robot's right side), which is
  /// also the axis the gripper closes along unless the wrist is turned, so misjudging it is what
  /// makes a grasp close on nothing. After a miss the person looks again, more carefully (the
  /// error's spread times `retry_aim_factor`).
  double toast_aim_sigma_x_m = 0.006, toast_aim_sigma_y_m = 0.012;
  double retry_aim_factor = 0.6;
  double plate_aim_sigma_m = 0.02;
  /// Line-up tolerances the person is content with, per axis (metres).
  double toast_tolerance_m = 0.008, plate_tolerance_m = 0.02;
  /// The carrying and letting-go heights, drawn per take (metres above the table).
  double carry_min_m = 0.08, carry_max_m = 0.16;
  double release_min_m = 0.03, release_max_m = 0.08;
  /// The chance per take of moving along both table axes at once rather than one after the
  /// other, and of starting toward the plate while still lifting.
  double diagonal_probability = 0.5;
  double lift_while_moving_probability = 0.4;
  /// Grasps closed on nothing before the person gives the take up.
  int max_grasp_attempts = 6;
};

/// A seeded simulated person at the tabletop's keyboard: each tick (0.1 s) it answers what the
/// scene shows with the keys a person would hold (arrows along the table's axes, Page Up/Down,
/// Space), as a TeleopCommand for the same Cartesian teleop the studio's keyboard drives. It
/// sees the objects where they are, up to its aiming errors, and the grip point late by its
/// reaction time, so it overshoots, corrects with taps, pauses, and sometimes misses the grasp.
/// What the learner must cope with: the tests' realistic person beside the ideal scripted one.
class SimulatedPerson {
 public:
  enum class Phase {
    kToToast,
    kDown,
    kGrasp,
    kReopen,
    kLift,
    kToPlate,
    kLower,
    kRelease,
    kRise,
    kGaveUp
  };

  explicit SimulatedPerson(const PersonStyle& style = {});

  /// A new take in the scene `world` shows now; the person's choices for it come from `seed`.
  void StartTake(const worlds::Tabletop& world, uint64_t seed);
  /// The keys for the next control period.
  TeleopCommand Next(const worlds::Tabletop& world);

  Phase phase() const { return phase_; }
  int grasp_attempts() const { return grasp_attempts_; }
  const PersonStyle& style() const { return style_; }

 private:
  /// Per-axis key state of one table axis, with the person's way of reaching a target on it:
  /// hold the key until the (late) view says it is there, then, after the first overshoot, taps.
  struct AxisHand {
    int key = 0;           ///< -1, 0, +1: the key held
    bool tapping = false;  ///< overshot once: taps from now on
    int wait_ticks = 0;    ///< after a tap, waiting to see where it went
    int last_sign = 0;     ///< the error's sign when the key was pressed
  };

  /// Steers one axis toward `target` as seen at `seen`; true once within `tolerance`.
  bool Steer(AxisHand& hand, double target, double seen, double tolerance);
  void Enter(Phase phase);
  void DrawToastAim(double scale);
  int ReactionTicks();
  Eigen::Vector3d SeenGrip() const;

  PersonStyle style_;
  Rng rng_{0};
  Phase phase_ = Phase::kToToast;
  AxisHand hands_[3];
  bool close_ = false;
  int pause_ticks_ = 0;
  int phase_ticks_ = 0;
  int wait_ticks_ = 0;
  int grasp_attempts_ = 0;
  bool diagonal_ = true, lift_while_moving_ = false;
  double carry_m_ = 0.12, release_m_ = 0.05, retry_rise_m_ = 0.03;
  Eigen::Vector2d toast_aim_ = Eigen::Vector2d::Zero(), plate_aim_ = Eigen::Vector2d::Zero();
  /// The grip positions of the last ticks, newest last: the person sees one a reaction late.
  std::deque<Eigen::Vector3d> seen_;
  int lag_ticks_ = 3;
};

const char* PersonPhaseName(SimulatedPerson::Phase phase);

/// The person as a recorder's teacher on `world` (both must outlive it): each tick its keys
/// through the Cartesian teleop, finished once the goal holds and the gripper is clear
/// (World::GoalHoldsAndClear), or when it gives up.
Teacher SimulatedPersonTeacher(worlds::Tabletop& world, SimulatedPerson& person);

}  // namespace recon::teach
