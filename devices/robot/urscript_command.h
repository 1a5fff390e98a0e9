#pragma once

// The few URScript lines RECON sends to a UR's script port, as text both ways: formatting for
// the client and strict parsing for the fake controller (which, like the real one, rejects a
// malformed program instead of guessing).

#include <array>
#include <optional>
#include <string>

namespace recon::robot {

/// One parsed script line.
struct UrScriptCommand {
  enum class Kind { kSpeedJ, kStopJ, kSetToolDigitalOut };
  Kind kind = Kind::kStopJ;
  std::array<double, 6> velocity_rad_s{};  ///< speedj
  double acceleration_rad_s2 = 0;          ///< speedj, stopj
  /// speedj: seconds before the robot decelerates unless a new speedj comes; 0 when the line
  /// gave none (the command then holds until replaced).
  double time_s = 0;
  int tool_output = 0;      ///< set_tool_digital_out
  bool tool_value = false;  ///< set_tool_digital_out
};

/// "speedj([qd1,...,qd6],a,t)\n" with 12 significant digits. UserError (naming the value) for a
/// non-finite velocity, a non-positive or non-finite acceleration or a negative or non-finite t:
/// whatever sits above, a NaN never reaches a robot.
std::string FormatSpeedJ(const std::array<double, 6>& velocity_rad_s, double acceleration_rad_s2,
                         double time_s);
/// "stopj(a)\n"; UserError for a non-positive or non-finite a.
std::string FormatStopJ(double acceleration_rad_s2);
/// "set_tool_digital_out(n,True)\n"; UserError unless 0 <= n <= 1 (a UR tool has two outputs).
std::string FormatSetToolDigitalOut(int output, bool value);

/// Parses one line (without or with its trailing newline; spaces allowed between tokens).
/// nullopt for anything else, including non-finite numbers and out-of-range arguments.
std::optional<UrScriptCommand> ParseUrScriptLine(const std::string& line);

}  // namespace recon::robot
