#include "engine/teach/simulated_person.h"

#include <algorithm>
#include <cmath>

namespace recon::teach {

namespace {

constexpr double kTick_s = worlds::Tabletop::kControlPeriod_s;
// How many past grip positions the person's late view keeps (more than the slowest reaction).
constexpr size_t kSeenHistory = 8;
// After a close, how long the person waits for the readout before looking again, at most.
constexpr int kGraspWaitTicks = 15;
// After letting go, how long the person rises before deciding the toast missed the plate.
constexpr int kRiseGiveUpTicks = 20;
// A hesitation lasts this long (seconds).
constexpr double kHesitationMin_s = 0.3, kHesitationMax_s = 1.0;
// The grasp band's top the person aims under, and its tolerance (metres).
constexpr double kBelowBandTop_m = 0.002, kBandTolerance_m = 0.002;
constexpr double kHeightTolerance_m = 0.015;
// After a miss the person rises this much before lining up again.
constexpr double kRetryRiseMin_m = 0.02, kRetryRiseMax_m = 0.04;

int Sign(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }
int Ticks(double seconds) { return std::max(0, static_cast<int>(std::lround(seconds / kTick_s))); }

}  // namespace

const char* PersonPhaseName(SimulatedPerson::Phase phase) {
  switch (phase) {
    case SimulatedPerson::Phase::kToToast:
      return "moving to the toast";
    case SimulatedPerson::Phase::kDown:
      return "going down to the toast";
    case SimulatedPerson::Phase::kGrasp:
      return "grasping";
    case SimulatedPerson::Phase::kReopen:
      return "opening after a miss";
    case SimulatedPerson::Phase::kLift:
      return "lifting";
    case SimulatedPerson::Phase::kToPlate:
      return "moving to the plate";
    case SimulatedPerson::Phase::kLower:
      return "lowering over the plate";
    case SimulatedPerson::Phase::kRelease:
      return "letting go";
    case SimulatedPerson::Phase::kRise:
      return "rising";
    case SimulatedPerson::Phase::kGaveUp:
      return "gave up";
  }
  return "?";
}

SimulatedPerson::SimulatedPerson(const PersonStyle& style) : style_(style) {}

void SimulatedPerson::StartTake(const worlds::Tabletop& world, uint64_t seed) {
  rng_.Seed(seed);
  grasp_attempts_ = 0;
  close_ = false;
  seen_.clear();
  seen_.push_back(world.arm().GripPosition());
  diagonal_ = rng_.Uniform() < style_.diagonal_probability;
  lift_while_moving_ = rng_.Uniform() < style_.lift_while_moving_probability;
  carry_m_ = rng_.Uniform(style_.carry_min_m, style_.carry_max_m);
  release_m_ = rng_.Uniform(style_.release_min_m, style_.release_max_m);
  plate_aim_ = {style_.plate_aim_sigma_m * rng_.Normal(), style_.plate_aim_sigma_m * rng_.Normal()};
  DrawToastAim(1.0);
  Enter(Phase::kToToast);
}

void SimulatedPerson::DrawToastAim(double scale) {
  toast_aim_ = {scale * style_.toast_aim_sigma_x_m * rng_.Normal(),
                scale * style_.toast_aim_sigma_y_m * rng_.Normal()};
}

int SimulatedPerson::ReactionTicks() {
  return std::max(1, Ticks(rng_.Uniform(style_.reaction_min_s, style_.reaction_max_s)));
}

void SimulatedPerson::Enter(Phase phase) {
  phase_ = phase;
  phase_ticks_ = 0;
  wait_ticks_ = 0;
  for (AxisHand& hand : hands_) hand = {};
  lag_ticks_ = ReactionTicks();
  if (rng_.Uniform() < style_.pause_probability) {
    pause_ticks_ = Ticks(rng_.Uniform(style_.pause_min_s, style_.pause_max_s));
  }
}

Eigen::Vector3d SimulatedPerson::SeenGrip() const {
  const size_t lag = std::min(seen_.size() - 1, static_cast<size_t>(lag_ticks_));
  return seen_[seen_.size() - 1 - lag];
}

bool SimulatedPerson::Steer(AxisHand& hand, double target, double seen, double tolerance) {
  const double error = target - seen;
  if (hand.wait_ticks > 0) {
    --hand.wait_ticks;
    hand.key = 0;
    return false;
  }
  // While a key is held the person expects the arm to go on a little after letting go.
  const double lead = hand.key != 0 && !hand.tapping
                          ? style_.anticipation * style_.speed_m_s * lag_ticks_ * kTick_s
                          : 0.0;
  if (hand.key != 0 && Sign(error) == hand.key && std::abs(error) <= tolerance + lead) {
    hand.key = 0;
    hand.wait_ticks = lag_ticks_;
    return false;
  }
  if (std::abs(error) <= tolerance) {
    // There, as far as the (late) view shows: let go, and call it there only once the view has
    // caught up with the arm standing still.
    const bool settled = hand.key == 0;
    if (hand.key != 0) hand.wait_ticks = lag_ticks_;
    hand.key = 0;
    return settled;
  }
  const int sign = Sign(error);
  if (hand.last_sign != 0 && sign != hand.last_sign) hand.tapping = true;  // went past it
  hand.last_sign = sign;
  if (hand.tapping) {
    // One tick's press, then watch where it went.
    if (hand.key != 0) {
      hand.key = 0;
      hand.wait_ticks = lag_ticks_;
    } else {
      hand.key = sign;
    }
  } else {
    hand.key = sign;
  }
  return false;
}

TeleopCommand SimulatedPerson::Next(const worlds::Tabletop& world) {
  seen_.push_back(world.arm().GripPosition());
  while (seen_.size() > kSeenHistory) seen_.pop_front();
  ++phase_ticks_;
  TeleopCommand command;
  const auto keys = [&] {
    command.velocity_m_s =
        style_.speed_m_s * Eigen::Vector3d(hands_[0].key, hands_[1].key, hands_[2].key);
    command.close_gripper = close_;
    command.finish = phase_ == Phase::kGaveUp;
    return command;
  };
  if (pause_ticks_ > 0) {
    --pause_ticks_;
    for (AxisHand& hand : hands_) hand.key = 0;
    return keys();
  }
  const bool moving = hands_[0].key != 0 || hands_[1].key != 0 || hands_[2].key != 0;
  if (moving && rng_.Uniform() < style_.hesitation_per_s * kTick_s) {
    pause_ticks_ = Ticks(rng_.Uniform(kHesitationMin_s, kHesitationMax_s));
    for (AxisHand& hand : hands_) hand.key = 0;
    return keys();
  }
  const Eigen::Vector3d seen = SeenGrip();
  const Eigen::Vector3d toast = world.ToastPosition(), plate = world.PlatePosition();
  const auto steer_xy = [&](const Eigen::Vector2d& target, double tolerance) {
    const bool x_on = Steer(hands_[0], target.x(), seen.x(), tolerance);
    if (!diagonal_ && !x_on) {
      hands_[1].key = 0;
      return false;
    }
    const bool y_on = Steer(hands_[1], target.y(), seen.y(), tolerance);
    return x_on && y_on;
  };
  const auto steer_z = [&](double target, double tolerance) {
    return Steer(hands_[2], target, seen.z(), tolerance);
  };
  switch (phase_) {
    case Phase::kToToast:
      if (steer_xy(toast.head<2>() + toast_aim_, style_.toast_tolerance_m)) Enter(Phase::kDown);
      break;
    case Phase::kDown: {
      const double band_top = world.GraspHeights().second;
      // Page Down until the readout says "low enough": the floor stops the tips in the band.
      if (seen.z() > band_top - kBelowBandTop_m + kBandTolerance_m) {
        hands_[2].key = -1;
      } else {
        hands_[2].key = 0;
        Enter(Phase::kGrasp);
      }
      break;
    }
    case Phase::kGrasp: {
      if (!close_) {
        close_ = true;
        ++grasp_attempts_;
        break;
      }
      const worlds::ToastGrip grip = world.GripOnToast();
      if (grip == worlds::ToastGrip::kClosing && phase_ticks_ < kGraspWaitTicks) break;
      // The readout has changed: take it in, then act.
      if (wait_ticks_ == 0) wait_ticks_ = lag_ticks_ + 1;
      if (--wait_ticks_ > 0) break;
      if (grip == worlds::ToastGrip::kHolding) {
        Enter(Phase::kLift);
      } else if (grasp_attempts_ >= style_.max_grasp_attempts) {
        Enter(Phase::kGaveUp);
      } else {
        Enter(Phase::kReopen);
        retry_rise_m_ = rng_.Uniform(kRetryRiseMin_m, kRetryRiseMax_m);
      }
      break;
    }
    case Phase::kReopen:
      close_ = false;
      if (steer_z(world.GraspHeights().second + retry_rise_m_, kBandTolerance_m * 2)) {
        // Look again, more carefully, and line up anew.
        DrawToastAim(std::pow(style_.retry_aim_factor, grasp_attempts_));
        Enter(Phase::kToToast);
      }
      break;
    case Phase::kLift: {
      const bool high = steer_z(carry_m_, kHeightTolerance_m);
      bool over = false;
      if (lift_while_moving_ && seen.z() > 0.05) {
        over = steer_xy(plate.head<2>() + plate_aim_, style_.plate_tolerance_m);
      }
      if (high) Enter(over ? Phase::kLower : Phase::kToPlate);
      break;
    }
    case Phase::kToPlate:
      if (steer_xy(plate.head<2>() + plate_aim_, style_.plate_tolerance_m)) Enter(Phase::kLower);
      break;
    case Phase::kLower:
      if (steer_z(release_m_, kHeightTolerance_m)) Enter(Phase::kRelease);
      break;
    case Phase::kRelease:
      if (close_) {
        close_ = false;
        wait_ticks_ = lag_ticks_ + 1;
      } else if (--wait_ticks_ <= 0) {
        Enter(Phase::kRise);
      }
      break;
    case Phase::kRise:
      hands_[2].key = 1;
      // The take ends by itself once the toast lies on the plate and the gripper is clear of
      // it; a person who sees the toast beside the plate gives the take up.
      if (phase_ticks_ > kRiseGiveUpTicks && !world.TaskSucceeded()) Enter(Phase::kGaveUp);
      break;
    case Phase::kGaveUp:
      for (AxisHand& hand : hands_) hand.key = 0;
      break;
  }
  return keys();
}

Teacher SimulatedPersonTeacher(worlds::Tabletop& world, SimulatedPerson& person) {
  return [&world, &person](const worlds::World&) {
    const TeleopCommand command = person.Next(world);
    return TeacherAction{CartesianTeleopAction(world, command), command.finish};
  };
}

}  // namespace recon::teach
