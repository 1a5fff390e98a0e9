#include "devices/robot/ur_arm.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "devices/robot/speedj_motion.h"
#include "devices/robot/ur_modes.h"
#include "engine/core/error.h"
#include "engine/core/steady_clock.h"

namespace recon::robot {

namespace {

void RequirePositive(double value, const char* name) {
  if (!std::isfinite(value) || value <= 0) {
    throw UserError(std::string("UR arm option ") + name + " must be a positive number, not " +
                    std::to_string(value));
  }
}

}  // namespace

UrArm::UrArm(Options options) : options_(std::move(options)) {
  RequirePositive(options_.acceleration_rad_s2, "acceleration_rad_s2");
  RequirePositive(options_.speedj_time_s, "speedj_time_s");
  RequirePositive(options_.stop_acceleration_rad_s2, "stop_acceleration_rad_s2");
  RequirePositive(options_.timeout_s, "timeout_s");
  RequirePositive(options_.stale_after_s, "stale_after_s");
  RtdeClient::Options rtde;
  rtde.host = options_.host;
  rtde.port = options_.rtde_port;
  rtde.frequency_hz = options_.rtde_frequency_hz;
  rtde.timeout_s = options_.timeout_s;
  rtde_ = std::make_unique<RtdeClient>(rtde);
  script_ =
      std::make_unique<UrScriptClient>(options_.host, options_.script_port, options_.timeout_s);
  if (!rtde_->WaitForData(options_.timeout_s)) {
    throw UserError("no RTDE data from " + rtde_->where() + " within " +
                    std::to_string(options_.timeout_s) + " s" +
                    (rtde_->last_error().empty() ? "" : ": " + rtde_->last_error()));
  }
}

RtdeState UrArm::Fresh() const {
  if (!rtde_->connected()) throw UserError("the UR5 is gone: " + rtde_->last_error());
  const std::optional<RtdeState> state = rtde_->Latest();
  const double age_s = state ? SteadySeconds() - state->received_s : 1e9;
  if (age_s > options_.stale_after_s) {
    char text[160];
    std::snprintf(text, sizeof(text), "no RTDE data from %s for %.2f s (the robot went silent)",
                  rtde_->where().c_str(), age_s);
    throw UserError(text);
  }
  return *state;
}

devices::JointState UrArm::State() const {
  const RtdeState s = Fresh();
  devices::JointState state;
  state.position_rad = s.actual_q_rad;
  state.velocity_rad_s = s.actual_qd_rad_s;
  state.gripper_opening = gripper_closed_ ? 0.0 : 1.0;
  state.timestamp_s = s.received_s;
  return state;
}

void UrArm::CommandJointVelocities(const std::array<double, 6>& velocity_rad_s) {
  const RtdeState s = Fresh();
  if (s.safety_mode != kSafetyModeNormal && s.safety_mode != 2 /* REDUCED */) {
    throw UserError("the UR5 at " + options_.host + " is in safety mode " +
                    SafetyModeName(s.safety_mode) +
                    ": it ignores motion until the stop is cleared on the pendant");
  }
  std::array<double, 6> clamped;
  for (size_t i = 0; i < 6; ++i) {
    // std::clamp keeps a NaN, which FormatSpeedJ then refuses.
    clamped[i] = std::clamp(velocity_rad_s[i], -SpeedjMotion::kMaxJointSpeed_rad_s,
                            SpeedjMotion::kMaxJointSpeed_rad_s);
  }
  script_->SpeedJ(clamped, options_.acceleration_rad_s2, options_.speedj_time_s);
}

void UrArm::CommandGripper(bool close) {
  Fresh();
  script_->SetToolDigitalOut(0, close);
  gripper_closed_ = close;
}

void UrArm::Stop() {
  if (!rtde_->connected()) throw UserError("the UR5 is gone: " + rtde_->last_error());
  script_->StopJ(options_.stop_acceleration_rad_s2);
}

std::string UrArm::Describe() const {
  char text[256];
  std::snprintf(text, sizeof(text),
                "UR5 at %s (controller %s; RTDE :%d at %g Hz, script :%d; speedj a %g rad/s^2, "
                "t %g s)",
                options_.host.c_str(), rtde_->controller_version().ToString().c_str(),
                options_.rtde_port, rtde_->frequency_hz(), options_.script_port,
                options_.acceleration_rad_s2, options_.speedj_time_s);
  return text;
}

}  // namespace recon::robot
