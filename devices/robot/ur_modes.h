#pragma once

#include <cstdint>
#include <string>

namespace recon::robot {

/// UR robot_mode values as RTDE reports them (RUNNING is the only one that moves).
inline constexpr int32_t kRobotModeRunning = 7;
/// UR safety_mode values: NORMAL, and the protective stop a collision or limit raises.
inline constexpr int32_t kSafetyModeNormal = 1;
inline constexpr int32_t kSafetyModeProtectiveStop = 3;

/// E.g. 7 -> "RUNNING", 3 -> "POWER_OFF"; "UNKNOWN(42)" for anything else.
inline std::string RobotModeName(int32_t mode) {
  static const char* const kNames[] = {"DISCONNECTED", "CONFIRM_SAFETY", "BOOTING",
                                       "POWER_OFF",    "POWER_ON",       "IDLE",
                                       "BACKDRIVE",    "RUNNING",        "UPDATING_FIRMWARE"};
  if (mode == -1) return "NO_CONTROLLER";
  if (mode >= 0 && mode <= 8) return kNames[mode];
  return "UNKNOWN(" + std::to_string(mode) + ")";
}

/// E.g. 1 -> "NORMAL", 3 -> "PROTECTIVE_STOP".
inline std::string SafetyModeName(int32_t mode) {
  static const char* const kNames[] = {"NORMAL",
                                       "REDUCED",
                                       "PROTECTIVE_STOP",
                                       "RECOVERY",
                                       "SAFEGUARD_STOP",
                                       "SYSTEM_EMERGENCY_STOP",
                                       "ROBOT_EMERGENCY_STOP",
                                       "VIOLATION",
                                       "FAULT",
                                       "VALIDATE_JOINT_ID",
                                       "UNDEFINED_SAFETY_MODE",
                                       "AUTOMATIC_MODE_SAFEGUARD_STOP",
                                       "SYSTEM_THREE_POSITION_ENABLING_STOP"};
  if (mode >= 1 && mode <= 13) return kNames[mode - 1];
  return "UNKNOWN(" + std::to_string(mode) + ")";
}

}  // namespace recon::robot
