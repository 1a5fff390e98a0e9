#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <random>
#include <string>

#include "ui/platform/frame_input.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::ui {

/// How a person's eyes and hands lag and err. The default is the ideal person: it acts the frame
/// it sees, never pauses and aims at the middle of what it sees. Realistic(seed) is a newcomer at
/// the keys, as a person was measured teaching in the studio: reaction times of 0.2-0.4 s (keys
/// pressed and let go that late, so the arm overshoots and is corrected), a pause to look at
/// each step of the task with probability 0.35 (0.4-1.8 s), and the toast's middle misjudged
/// along the view's depth (a Gaussian error of 12 % of its size in the view, 7 % across), judged
/// again more carefully after a grasp that closed on nothing. Every draw comes from `seed`.
struct PersonPace {
  uint64_t seed = 0;
  double reaction_min_s = 0, reaction_max_s = 0;
  double pause_probability = 0, pause_min_s = 0, pause_max_s = 0;
  double depth_aim_sigma = 0, across_aim_sigma = 0;
  double retry_aim_factor = 0.6;

  static PersonPace Realistic(uint64_t seed);
  bool ideal() const {
    return reaction_max_s <= 0 && pause_probability <= 0 && depth_aim_sigma <= 0;
  }
};

/// A scripted person giving a keyboard demonstration of the tabletop task from what the Record
/// screen shows, and nothing else: the teacher's 3-D view (the toast and the plate picked out by
/// their colours once, as the take starts; the drop line's spot under the gripper), the height
/// readout with its grasp band, and the grip's state ("Holding the toast", "Closed on nothing").
/// It never reads the simulator's truth. It answers each frame with the keys a person would hold:
/// the arrows to put the spot on the toast, Page Down to the grasp band, Space, Page Up, the
/// arrows to the plate, down, Space, up; a grasp that closes on nothing is opened, lined up
/// again and retried, as a person would.
///
/// What measures whether the screen is enough to teach by: StudioPersonTest gives a take on
/// new scenes and counts first-try successes.
class KeyboardPerson {
 public:
  enum class Phase {
    kWaiting,   ///< for the countdown to end
    kToToast,   ///< arrows: the spot onto the toast; then down to the grasp band
    kGrasp,     ///< Space, and wait to see whether it holds
    kReopen,    ///< closed on nothing: open again and rise a little before the next try
    kLift,      ///< up to carrying height
    kToPlate,   ///< arrows: the spot onto the plate's centre
    kLower,     ///< down over the plate
    kRelease,   ///< Space: the toast drops
    kRetreat,   ///< up until the take ends (the studio keeps a done take)
    kFinished,  ///< the take ended
    kLost,      ///< could not see the toast or the plate
  };

  explicit KeyboardPerson(const PersonPace& pace = {});

  using Clock = std::chrono::steady_clock;

  /// The keys for the next frame, given what the screen shows at `now` (the studio's time: a
  /// reaction time or a pause lasts that long on the studio's clock).
  FrameInput Next(const StudioSnapshot& s, Clock::time_point now = Clock::now());

  Phase phase() const { return phase_; }
  /// How many times it closed the gripper over the toast.
  int grasp_attempts() const { return grasp_attempts_; }
  /// What it is doing and what it sees, for a test's failure message.
  std::string Describe() const;

 private:
  struct Target {
    float x = 0, y = 0;  ///< in the view's pixels
    float tolerance_x = 0, tolerance_y = 0;
    float width = 0, height = 0;  ///< of what the view shows, pixels
  };

  /// Finds the toast and the plate in the 3-D view; false when either is not in sight.
  bool Look(const TeacherView& view);
  /// What the person decides now (Decide) reaches the keys a reaction time later.
  FrameInput Decide(const StudioSnapshot& s);
  FrameInput Delayed(FrameInput decision);
  /// Where the person thinks the toast's middle is: its middle, off by the aim error.
  void Aim(double scale);
  /// How a person steers one axis of the view: a key held toward the target's middle until the
  /// spot is on the middle (not merely near it), and, once they have gone past the target,
  /// taps with a look between them.
  struct Axis {
    int last_want = 0;
    int holding = 0;  ///< the key held toward the middle, until the spot reaches it
    bool tapping = false, pressed = false;
    std::chrono::steady_clock::time_point wait_until{};
  };
  /// The key for one axis whose target lies `error` pixels away (AxisKey's rule above).
  int AxisKey(Axis& axis, float error, float tolerance);
  /// The arrows that move the spot toward `target`; true once it has stayed on it.
  bool Steer(const StudioSnapshot& s, const Target& target, FrameInput& keys);
  void Enter(Phase phase);

  Phase phase_ = Phase::kWaiting;
  Target toast_, plate_;
  int grasp_attempts_ = 0;
  int settled_frames_ = 0;   ///< consecutive new views with the spot on the target
  uint64_t last_view_ = 0;   ///< the teacher view's frame number seen last
  bool space_sent_ = false;  ///< Space pressed in this phase
  Clock::time_point phase_started_{};
  Clock::time_point now_{};  ///< the time of the frame being answered
  bool looked_yet_ = false;
  std::string lost_;

  Phase ended_in_ = Phase::kFinished;  ///< what it was doing when the take ended
  PersonPace pace_;
  Axis axes_[2];  ///< the view's right and down
  std::mt19937_64 rng_;
  Target toast_seen_;  ///< the toast's middle as the view shows it, before the aim error
  Clock::time_point paused_until_{};
  double lag_s_ = 0;
  struct Decision {
    Clock::time_point at;
    FrameInput keys;
  };
  std::deque<Decision> decisions_;  ///< made, not yet reached the keys
  FrameInput held_;                 ///< the keys down now
};

const char* PhaseName(KeyboardPerson::Phase phase);

}  // namespace recon::ui
