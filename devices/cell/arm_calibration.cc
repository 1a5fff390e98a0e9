#include "devices/cell/arm_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "engine/core/error.h"
#include "engine/safety/ur5_kinematics.h"

namespace recon::cell {

namespace {

// A grid of `points` over the region, row by row in a serpentine (short moves), the heights
// alternating like a checkerboard.
std::vector<Eigen::Vector3d> PlanPlaces(const ArmCalibrationOptions& o) {
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(o.points))));
  const int rows = (o.points + cols - 1) / cols;
  std::vector<Eigen::Vector3d> plan;
  for (int r = 0; r < rows && static_cast<int>(plan.size()) < o.points; ++r) {
    for (int i = 0; i < cols && static_cast<int>(plan.size()) < o.points; ++i) {
      const int c = r % 2 == 0 ? i : cols - 1 - i;
      const double fx = rows > 1 ? static_cast<double>(r) / (rows - 1) : 0.5;
      const double fy = cols > 1 ? static_cast<double>(c) / (cols - 1) : 0.5;
      plan.emplace_back(o.min_xy.x() + fx * (o.max_xy.x() - o.min_xy.x()),
                        o.min_xy.y() + fy * (o.max_xy.y() - o.min_xy.y()),
                        (r + c) % 2 == 0 ? o.low_m : o.high_m);
    }
  }
  return plan;
}

}  // namespace

ArmCalibration::ArmCalibration(ArmCalibrationOptions options, teach::TeleopArm arm)
    : options_(std::move(options)), arm_(std::move(arm)) {
  const ArmCalibrationOptions& o = options_;
  if (o.points < 3) throw UserError("a calibration needs at least 3 places for a rigid fit");
  for (double v : {o.low_m, o.high_m, o.speed_m_s, o.arrive_tolerance_m, o.settle_s, o.hold_s,
                   o.move_timeout_s, o.beacon_silent_s}) {
    if (!(v > 0) || !std::isfinite(v)) {
      throw UserError("arm calibration: heights, times and speeds must be positive numbers");
    }
  }
  if (!o.beacon_offset_m.allFinite()) {
    throw UserError("arm calibration: the beacon's offset from the tool must be finite");
  }
  if (!(o.max_xy.x() > o.min_xy.x()) || !(o.max_xy.y() > o.min_xy.y())) {
    throw UserError("arm calibration: the region's max x and y must exceed its min");
  }
  if (o.min_uwb_samples < 1) {
    throw UserError("arm calibration: at least one beacon reading per place");
  }
  plan_ = PlanPlaces(o);
  status_.total = static_cast<int>(plan_.size());
}

Eigen::Vector3d ArmCalibration::BeaconAt(const std::array<double, 6>& q_rad) const {
  return arm_.base_in_table * safety::Ur5ToolPoint(q_rad, arm_.tool_offset_m) +
         options_.beacon_offset_m;
}

std::array<double, 6> ArmCalibration::Update(const std::array<double, 6>& q_rad,
                                             const std::vector<devices::BeaconSample>& samples,
                                             double now_s, double period_s, bool arm_held) {
  std::array<double, 6> stay{};
  if (!started_) {
    started_ = true;
    phase_start_s_ = now_s;
    last_reading_s_ = now_s;  // silence is counted from the start
    last_now_s_ = now_s;
  }
  if (arm_held) phase_start_s_ += now_s - last_now_s_;  // a held arm is not late
  last_now_s_ = now_s;
  if (Done()) return stay;
  const Eigen::Vector3d beacon = BeaconAt(q_rad);
  for (const devices::BeaconSample& sample : samples) {
    if (!options_.beacon.empty() && sample.beacon != options_.beacon) continue;
    status_.beacon_uwb_m = sample.position_uwb_m;
    last_reading_s_ = now_s;
    if (holding_ && !arm_held && now_s >= phase_start_s_ + options_.settle_s) {
      hold_uwb_.push_back(sample.position_uwb_m);
    }
  }
  status_.beacon_silent = now_s - last_reading_s_ > options_.beacon_silent_s;
  const Eigen::Vector3d target = plan_[static_cast<size_t>(next_)];
  const double to_go = (target - beacon).norm();
  std::array<double, 6> velocity = stay;
  status_.held_fraction = 0;
  if (arm_held) {
    // Nothing moves and nothing counts while the e-stop holds the arm.
  } else if (!holding_) {
    if (to_go <= options_.arrive_tolerance_m) {
      holding_ = true;
      phase_start_s_ = now_s;
      hold_truth_.clear();
      hold_uwb_.clear();
    } else if (now_s - phase_start_s_ > options_.move_timeout_s) {
      ++skipped_;
      char text[160];
      std::snprintf(text, sizeof(text),
                    "Place %d could not be reached in %.0f s (still %.0f cm away): skipped. ",
                    next_ + 1, options_.move_timeout_s, 100 * to_go);
      last_skip_ = text;
      NextPlace(now_s);
    } else {
      // Proportional into the place, at most speed_m_s.
      teach::TeleopCommand command;
      command.velocity_m_s = (target - beacon) * 2.0;
      const double speed = command.velocity_m_s.norm();
      if (speed > options_.speed_m_s) command.velocity_m_s *= options_.speed_m_s / speed;
      const std::vector<float> u = teach::CartesianTeleopAction(
          q_rad, command, arm_, std::clamp(period_s, 0.01, 0.2), teach::CartesianTeleopLimits{});
      for (int i = 0; i < 6; ++i) velocity[static_cast<size_t>(i)] = u[static_cast<size_t>(i)];
    }
  }
  if (holding_ && !arm_held) {
    if (now_s >= phase_start_s_ + options_.settle_s) hold_truth_.push_back(beacon);
    status_.held_fraction = std::min(1.0, (now_s - phase_start_s_) / options_.hold_s);
    if (status_.held_fraction >= 1.0 &&
        static_cast<int>(hold_uwb_.size()) >= options_.min_uwb_samples && !hold_truth_.empty()) {
      poses_.push_back(PoseFromHold(hold_truth_, hold_uwb_));
      last_skip_.clear();
      NextPlace(now_s);
    }
  }
  status_.taken = static_cast<int>(poses_.size());
  Prompt(now_s, to_go, arm_held);
  return velocity;
}

void ArmCalibration::NextPlace(double now_s) {
  ++next_;
  holding_ = false;
  phase_start_s_ = now_s;
  hold_truth_.clear();
  hold_uwb_.clear();
}

void ArmCalibration::Prompt(double now_s, double to_go_m, bool arm_held) {
  char text[320];
  const int place = std::min(next_ + 1, static_cast<int>(plan_.size()));
  const int total = static_cast<int>(plan_.size());
  if (Done()) {
    std::snprintf(text, sizeof(text), "All %d places done: %d taken, %d skipped.", total,
                  static_cast<int>(poses_.size()), skipped_);
  } else if (arm_held) {
    std::snprintf(text, sizeof(text),
                  "Place %d of %d: the e-stop holds the arm. Release it to go on.", place, total);
  } else if (status_.beacon_silent) {
    std::snprintf(text, sizeof(text),
                  "No reading from the beacon on the arm for %.0f s: check that it is switched "
                  "on and its port plugged in. The calibration goes on when it reports again.",
                  now_s - last_reading_s_);
  } else if (!holding_) {
    std::snprintf(text, sizeof(text),
                  "%sPlace %d of %d: the arm carries the beacon there (%.0f cm to go). Keep "
                  "clear of the arm.",
                  last_skip_.c_str(), place, total, 100 * to_go_m);
  } else {
    std::snprintf(text, sizeof(text), "Place %d of %d: holding still, %d of %d readings.", place,
                  total, static_cast<int>(hold_uwb_.size()), options_.min_uwb_samples);
  }
  status_.prompt = text;
}

calib::CalibrationReport ArmCalibration::Fit() const {
  if (poses_.size() < 3) {
    throw UserError("the arm reached only " + std::to_string(poses_.size()) + " of " +
                    std::to_string(plan_.size()) + " calibration places (" +
                    std::to_string(skipped_) +
                    " skipped): a fit needs 3. Check the arm's reach and the profile's "
                    "beacon_on_arm offset.");
  }
  std::vector<calib::CalibrationPoint> points;
  for (const CollectedPose& pose : poses_) points.push_back(pose.point);
  return calib::Calibrate(points, options_.calibration);
}

}  // namespace recon::cell
