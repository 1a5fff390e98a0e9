#include "ui/testing/keyboard_person.h"

#include <imgui.h>

#include <cmath>
#include <cstdio>

#include "ui/testing/colour_blob.h"

namespace recon::ui {

namespace {

// The heights a person aims for on the readout (metres above the table): carrying the toast
// well above the bowl, letting it go a little above the plate, and rising after a failed grasp.
constexpr float kCarryHeight_m = 0.12f;
constexpr float kReleaseHeight_m = 0.06f;
constexpr float kRetryRise_m = 0.03f;
constexpr float kRetreatHeight_m = 0.28f;
// How close the spot must be to a target, as a share of the target's size in the view (the
// toast is 10 cm across: 7 % is 7 mm), and for how many new views in a row.
constexpr float kToastTolerance = 0.07f;
constexpr float kPlateTolerance = 0.10f;
constexpr int kSettledViews = 3;
// Where a held key is let go: this share of the tolerance from the target's middle.
constexpr float kMiddleShare = 0.25f;
constexpr int kMaxGraspAttempts = 5;

// The toast's crust and the plate's blue, by the ratios of the channels (which the lights and
// shadows scale together): the table is nearly grey, the bowl red, the drop line yellow (little
// blue), the robot's joint caps a greyer blue than the plate.
bool IsToast(int r, int g, int b) {
  return r > 60 && g > 0.55 * r && g < 0.82 * r && b > 0.2 * r && b < 0.5 * r;
}
bool IsPlate(int r, int g, int b) { return b > 80 && b > 2.2 * g && b > 3 * r; }

/// Where to aim on an object seen from above at an angle: the middle of its top face. The near
/// side shows as a band under it, so the top face's middle sits above the patch's centroid.
float TopFaceMiddle(const ColourBlob& blob) {
  return blob.top + 0.42f * static_cast<float>(blob.bottom - blob.top);
}

// FrameInput carries ImGuiKey values (the window maps each to its own io.KeysDown slot).
void Hold(FrameInput& keys, ImGuiKey key) { keys.keys_down.push_back(key); }
void Press(FrameInput& keys, ImGuiKey key) { keys.keys_pressed.push_back(key); }

}  // namespace

const char* PhaseName(KeyboardPerson::Phase phase) {
  switch (phase) {
    case KeyboardPerson::Phase::kWaiting:
      return "waiting for the take";
    case KeyboardPerson::Phase::kToToast:
      return "moving to the toast";
    case KeyboardPerson::Phase::kGrasp:
      return "grasping";
    case KeyboardPerson::Phase::kReopen:
      return "opening after a miss";
    case KeyboardPerson::Phase::kLift:
      return "lifting";
    case KeyboardPerson::Phase::kToPlate:
      return "moving to the plate";
    case KeyboardPerson::Phase::kLower:
      return "lowering over the plate";
    case KeyboardPerson::Phase::kRelease:
      return "letting go";
    case KeyboardPerson::Phase::kRetreat:
      return "rising";
    case KeyboardPerson::Phase::kFinished:
      return "finished";
    case KeyboardPerson::Phase::kLost:
      return "lost";
  }
  return "?";
}

std::string KeyboardPerson::Describe() const {
  char text[320];
  const std::string phase =
      phase_ == Phase::kFinished && ended_in_ != Phase::kFinished
          ? std::string("finished (the take ended while ") + PhaseName(ended_in_) + ")"
          : PhaseName(phase_);
  std::snprintf(text, sizeof(text),
                "%s after %d grasp attempt(s); toast seen at (%.0f, %.0f) px, plate at (%.0f, "
                "%.0f) px%s%s",
                phase.c_str(), grasp_attempts_, toast_.x, toast_.y, plate_.x, plate_.y,
                lost_.empty() ? "" : ": ", lost_.c_str());
  return text;
}

void KeyboardPerson::Enter(Phase phase) {
  phase_ = phase;
  axes_[0] = axes_[1] = Axis{};
  settled_frames_ = 0;
  space_sent_ = false;
  phase_started_ = now_;
  if (pace_.ideal()) return;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  lag_s_ = pace_.reaction_min_s + (pace_.reaction_max_s - pace_.reaction_min_s) * uniform(rng_);
  // At each step of the task the person may stop to look before going on.
  if (phase != Phase::kFinished && phase != Phase::kLost &&
      uniform(rng_) < pace_.pause_probability) {
    const double pause =
        pace_.pause_min_s + (pace_.pause_max_s - pace_.pause_min_s) * uniform(rng_);
    paused_until_ = phase_started_ + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(pause));
  }
  // A grasp that closed on nothing: look at the toast again, more carefully.
  if (phase == Phase::kReopen) Aim(std::pow(pace_.retry_aim_factor, grasp_attempts_));
}

bool KeyboardPerson::Look(const TeacherView& view) {
  const std::optional<ColourBlob> toast = LargestBlob(view.image, IsToast);
  const std::optional<ColourBlob> plate = LargestBlob(view.image, IsPlate);
  if (!toast || !plate) {
    lost_ = !toast ? "no toast in the 3-D view" : "no plate in the 3-D view";
    return false;
  }
  const auto target = [](const ColourBlob& blob, float share) {
    Target t;
    t.x = blob.centre_x;
    t.y = TopFaceMiddle(blob);
    t.tolerance_x = std::max(1.0f, share * static_cast<float>(blob.right - blob.left + 1));
    t.tolerance_y = std::max(1.0f, share * static_cast<float>(blob.bottom - blob.top + 1));
    t.width = static_cast<float>(blob.right - blob.left + 1);
    t.height = static_cast<float>(blob.bottom - blob.top + 1);
    return t;
  };
  toast_seen_ = toast_ = target(*toast, kToastTolerance);
  plate_ = target(*plate, kPlateTolerance);
  Aim(1.0);
  return true;
}

PersonPace PersonPace::Realistic(uint64_t seed) {
  PersonPace pace;
  pace.seed = seed;
  pace.reaction_min_s = 0.2;
  pace.reaction_max_s = 0.4;
  pace.pause_probability = 0.35;
  pace.pause_min_s = 0.4;
  pace.pause_max_s = 1.8;
  pace.depth_aim_sigma = 0.12;
  pace.across_aim_sigma = 0.07;
  return pace;
}

KeyboardPerson::KeyboardPerson(const PersonPace& pace) : pace_(pace), rng_(pace.seed) {
  lag_s_ = pace_.reaction_min_s;
}

void KeyboardPerson::Aim(double scale) {
  if (pace_.depth_aim_sigma <= 0 && pace_.across_aim_sigma <= 0) return;
  std::normal_distribution<double> normal(0.0, 1.0);
  // The view's vertical is the table's depth from where the person sits: the hardest to judge.
  toast_.x = toast_seen_.x +
             static_cast<float>(scale * pace_.across_aim_sigma * normal(rng_)) * toast_seen_.width;
  toast_.y = toast_seen_.y +
             static_cast<float>(scale * pace_.depth_aim_sigma * normal(rng_)) * toast_seen_.height;
}

FrameInput KeyboardPerson::Delayed(FrameInput decision) {
  const Clock::time_point now = now_;
  decisions_.push_back({now, std::move(decision)});
  FrameInput keys;
  const Clock::time_point due =
      now - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(lag_s_));
  while (!decisions_.empty() && decisions_.front().at <= due) {
    held_ = std::move(decisions_.front().keys);
    // A key pressed once (Space, Enter) is pressed once, when its decision reaches the hands.
    keys.keys_pressed.insert(keys.keys_pressed.end(), held_.keys_pressed.begin(),
                             held_.keys_pressed.end());
    decisions_.pop_front();
  }
  keys.keys_down = held_.keys_down;
  return keys;
}

int KeyboardPerson::AxisKey(Axis& axis, float error, float tolerance) {
  // A person moves the spot to where they think the middle is, not to the first place that is
  // near enough: a key held toward the target stays down until the spot reaches the middle
  // (within kMiddleShare of the tolerance) or passes it. Only a spot that drifts out of the
  // tolerance again is moved again. Stopping at the tolerance's edge instead put every grasp
  // of the ideal person 7 mm short of the toast's middle on the side it came from.
  const int outside = error > tolerance ? 1 : (error < -tolerance ? -1 : 0);
  const int side = error > 0 ? 1 : (error < 0 ? -1 : 0);
  if (axis.holding != 0 && (side != axis.holding || std::abs(error) <= kMiddleShare * tolerance)) {
    axis.holding = 0;
  }
  if (outside != 0) axis.holding = outside;
  const int want = axis.holding;
  if (pace_.ideal()) return want;
  // A person who lags sees an overshoot late; after the first, they tap: one press, then wait
  // for the view to show where it went (a reaction time) before the next.
  const Clock::time_point now = now_;
  if (want != 0 && axis.last_want != 0 && want != axis.last_want) axis.tapping = true;
  if (want != 0) axis.last_want = want;
  if (!axis.tapping) return want;
  // Tapping, each tap is judged by whether the spot is near enough yet.
  axis.holding = 0;
  if (outside == 0) return 0;
  if (now < axis.wait_until) return 0;
  if (axis.pressed) {
    axis.pressed = false;
    axis.wait_until =
        now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(lag_s_));
    return 0;
  }
  axis.pressed = true;
  return want;
}

bool KeyboardPerson::Steer(const StudioSnapshot& s, const Target& target, FrameInput& keys) {
  const float ex = target.x - s.teacher_view.spot_pixel[0];
  const float ey = target.y - s.teacher_view.spot_pixel[1];
  const int right = AxisKey(axes_[0], ex, target.tolerance_x);
  const int down = AxisKey(axes_[1], ey, target.tolerance_y);  // image rows grow downwards
  if (right > 0) Hold(keys, ImGuiKey_RightArrow);
  if (right < 0) Hold(keys, ImGuiKey_LeftArrow);
  if (down < 0) Hold(keys, ImGuiKey_UpArrow);
  if (down > 0) Hold(keys, ImGuiKey_DownArrow);
  // On it once near enough and no longer moving toward the middle.
  const bool on = std::abs(ex) <= target.tolerance_x && std::abs(ey) <= target.tolerance_y &&
                  right == 0 && down == 0;
  if (!on) {
    settled_frames_ = 0;
  } else if (s.teacher_view.frame != last_view_) {
    ++settled_frames_;
  }
  return settled_frames_ >= kSettledViews;
}

FrameInput KeyboardPerson::Next(const StudioSnapshot& s, Clock::time_point now) {
  now_ = now;
  if (!looked_yet_) phase_started_ = now;
  looked_yet_ = true;
  if (pace_.ideal()) return Decide(s);
  FrameInput decision;
  if (now_ >= paused_until_ || phase_ == Phase::kWaiting) {
    decision = Decide(s);
  } else {
    last_view_ = s.teacher_view.frame;  // looking, the hands still
    if (!s.recording && phase_ != Phase::kLost) {
      ended_in_ = phase_;
      Enter(Phase::kFinished);
    }
  }
  return Delayed(std::move(decision));
}

FrameInput KeyboardPerson::Decide(const StudioSnapshot& s) {
  FrameInput keys;
  const float height = s.grip_m[2];
  const float grasp_top = s.grip.grasp_max_m;
  const double in_phase_s = std::chrono::duration<double>(now_ - phase_started_).count();
  if (phase_ != Phase::kWaiting && phase_ != Phase::kLost && phase_ != Phase::kFinished &&
      !s.recording) {
    ended_in_ = phase_;
    Enter(Phase::kFinished);
  }
  switch (phase_) {
    case Phase::kWaiting:
      if (s.recording && s.countdown_s <= 0 && s.teacher_view.available &&
          s.teacher_view.image.width > 0) {
        Enter(Look(s.teacher_view) ? Phase::kToToast : Phase::kLost);
      }
      break;
    case Phase::kToToast: {
      const bool over = Steer(s, toast_, keys);
      // Down while lined up; the last centimetres only once the spot has settled on the toast.
      if (height > grasp_top - 0.001f && (over || height > grasp_top + 0.03f)) {
        Hold(keys, ImGuiKey_PageDown);
      }
      if (over && height <= grasp_top - 0.001f) Enter(Phase::kGrasp);
      break;
    }
    case Phase::kGrasp:
      if (!space_sent_) {
        Press(keys, ImGuiKey_Space);
        space_sent_ = true;
        ++grasp_attempts_;
      } else if (s.grip.state == GripState::kHolding) {
        Enter(Phase::kLift);
      } else if (s.grip.state == GripState::kClosedOnNothing || in_phase_s > 3.0) {
        Enter(grasp_attempts_ >= kMaxGraspAttempts ? Phase::kLost : Phase::kReopen);
        if (phase_ == Phase::kLost) lost_ = "the gripper kept closing on nothing";
      }
      break;
    case Phase::kReopen:
      if (!space_sent_ && s.gripper_closed) {
        Press(keys, ImGuiKey_Space);
        space_sent_ = true;
      } else if (s.grip.state == GripState::kOpen) {
        if (height < grasp_top + kRetryRise_m) {
          Hold(keys, ImGuiKey_PageUp);
        } else {
          Enter(Phase::kToToast);
        }
      }
      break;
    case Phase::kLift:
      if (height < kCarryHeight_m) {
        Hold(keys, ImGuiKey_PageUp);
      } else {
        Enter(Phase::kToPlate);
      }
      break;
    case Phase::kToPlate:
      if (Steer(s, plate_, keys)) Enter(Phase::kLower);
      break;
    case Phase::kLower:
      Steer(s, plate_, keys);
      if (height > kReleaseHeight_m) {
        Hold(keys, ImGuiKey_PageDown);
      } else {
        Enter(Phase::kRelease);
      }
      break;
    case Phase::kRelease:
      if (!space_sent_) {
        Press(keys, ImGuiKey_Space);
        space_sent_ = true;
      } else if (s.grip.state == GripState::kOpen) {
        Enter(Phase::kRetreat);
      }
      break;
    case Phase::kRetreat:
      // The studio keeps a take by itself once the toast is on the plate and the arm has risen;
      // a person who sees it still running at the top keeps it with Enter.
      if (height < kRetreatHeight_m) {
        Hold(keys, ImGuiKey_PageUp);
      } else if (in_phase_s > 2.0) {
        Press(keys, ImGuiKey_Enter);
      }
      break;
    case Phase::kFinished:
    case Phase::kLost:
      break;
  }
  last_view_ = s.teacher_view.frame;
  return keys;
}

}  // namespace recon::ui
