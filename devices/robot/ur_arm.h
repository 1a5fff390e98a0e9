#pragma once

#include <array>
#include <memory>
#include <string>

#include "devices/robot/rtde_client.h"
#include "devices/robot/urscript_client.h"
#include "engine/devices/arm.h"

namespace recon::robot {

/// A real UR5 (or FakeUrController) as a devices::Arm: state from RTDE (port 30004), commands as
/// URScript lines on the script port (30002).
///
/// - State(): the latest RTDE package, stamped with its arrival on the host's steady clock
///   (RtdeState::received_s, seconds). UserError when the connection is gone or no package came
///   for `stale_after_s`.
/// - CommandJointVelocities(qd): `speedj(qd, a, t)` with qd clamped to the UR5's pi rad/s. The
///   short t is the watchdog: if commands stop coming the controller itself decelerates to rest t
///   seconds after the last one, whatever happens to this process. Refused (UserError, nothing
///   sent) for non-finite values, and while the robot is not in NORMAL/REDUCED safety mode (e.g.
///   after a protective stop, which must be cleared on the pendant).
/// - Stop(): `stopj(stop_acceleration)`.
/// - CommandGripper(close): `set_tool_digital_out(0, True/False)`. Assumes a two-finger gripper
///   wired to tool digital output 0 that closes while the output is high (e.g. a Robotiq Hand-E in
///   I/O mode or a pneumatic gripper's valve). The opening in State() is the commanded one (1 open,
///   0 closed): the gripper reports no feedback over this wiring.
class UrArm final : public devices::Arm {
 public:
  struct Options {
    std::string host;
    int rtde_port = 30004;
    int script_port = 30002;
    double rtde_frequency_hz = 125;
    double acceleration_rad_s2 = 1.4;       ///< speedj's a
    double speedj_time_s = 0.1;             ///< speedj's t: how long one command holds
    double stop_acceleration_rad_s2 = 2.0;  ///< stopj's a
    double timeout_s = 2.0;                 ///< to connect and for the first RTDE package
    double stale_after_s = 0.5;             ///< State() fails when RTDE is silent this long
  };

  /// Connects RTDE and the script port and waits for the first state. UserError naming
  /// host:port for whatever does not answer, and for non-positive a, t or timeouts.
  explicit UrArm(Options options);

  devices::JointState State() const override;
  void CommandJointVelocities(const std::array<double, 6>& velocity_rad_s) override;
  void CommandGripper(bool close) override;
  void Stop() override;
  /// E.g. "UR5 at 192.168.1.10 (controller 5.11.0.108; RTDE :30004 at 125 Hz, script :30002;
  /// speedj a 1.4 rad/s^2, t 0.1 s)".
  std::string Describe() const override;

  const RtdeClient& rtde() const { return *rtde_; }
  const Options& options() const { return options_; }

 private:
  /// The latest RTDE state, or UserError when the robot is gone or silent.
  RtdeState Fresh() const;

  Options options_;
  std::unique_ptr<RtdeClient> rtde_;
  std::unique_ptr<UrScriptClient> script_;
  bool gripper_closed_ = false;
};

}  // namespace recon::robot
