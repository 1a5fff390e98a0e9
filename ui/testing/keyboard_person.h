#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "ui/platform/frame_input.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::ui {

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

  /// The keys for the next frame, given what the screen shows now.
  FrameInput Next(const StudioSnapshot& s);

  Phase phase() const { return phase_; }
  /// How many times it closed the gripper over the toast.
  int grasp_attempts() const { return grasp_attempts_; }
  /// What it is doing and what it sees, for a test's failure message.
  std::string Describe() const;

 private:
  using Clock = std::chrono::steady_clock;
  struct Target {
    float x = 0, y = 0;  ///< in the view's pixels
    float tolerance_x = 0, tolerance_y = 0;
  };

  /// Finds the toast and the plate in the 3-D view; false when either is not in sight.
  bool Look(const TeacherView& view);
  /// The arrows that move the spot toward `target`; true once it has stayed on it.
  bool Steer(const StudioSnapshot& s, const Target& target, FrameInput& keys);
  void Enter(Phase phase);

  Phase phase_ = Phase::kWaiting;
  Target toast_, plate_;
  int grasp_attempts_ = 0;
  int settled_frames_ = 0;   ///< consecutive new views with the spot on the target
  uint64_t last_view_ = 0;   ///< the teacher view's frame number seen last
  bool space_sent_ = false;  ///< Space pressed in this phase
  Clock::time_point phase_started_ = Clock::now();
  std::string lost_;
};

const char* PhaseName(KeyboardPerson::Phase phase);

}  // namespace recon::ui
