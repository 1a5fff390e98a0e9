#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/stepped_clock.h"

namespace recon::studio {

struct StudioOptions {
  /// Opened if it holds a session, created otherwise; empty: start at the session picker.
  std::string session_dir;
  /// Gamepads to look for (empty: /dev/input/js*, looked for every 2 s while none is open).
  std::vector<std::string> gamepad_paths;
  /// The list of recent sessions (empty: RecentSessions::DefaultPath()).
  std::string recent_sessions_file;
  std::string world = "tabletop";
  int image_size = 64;  ///< the policy camera (new sessions)
  uint64_t seed = 1;    ///< new sessions
  /// New sessions' simulated beacon noise (metres); unset: the world's default (a DWM1001's on
  /// the tabletop, worlds::DefaultBeaconNoise).
  std::optional<double> beacon_noise_sigma;
  /// New sessions' tabletop layout ("paper" or "wide").
  std::string layout = "paper";
  /// New sessions' demonstration noise (DART, rad/s; 0 = off); unset: the world's default in the
  /// simulated cell, off on real hardware.
  std::optional<double> demo_noise_sigma;
  /// Demonstrations run at the control rate (10 Hz), as a person teaching would see them; off,
  /// they run as fast as the simulation goes (tests, demos).
  bool real_time = true;
  /// The studio's time: a script's frames move it (SteppedClock), so what a scripted teacher
  /// does is the same on any machine; null: the steady clock, as a person at the desk needs.
  std::shared_ptr<SteppedClock> clock;
  /// A person's take (keyboard, gamepad) starts this many seconds after Start, counted down on
  /// screen, so their hands are on the keys when the arm starts listening; 0: at once.
  double countdown_s = 3.0;
  int train_steps = 0;  ///< at most this many steps per method; 0: the world's recipe
  int rollout_tests = 10;
  /// Places per side of the grid "Check what it looks at" moves each object over.
  int probe_grid = 10;
  int calibration_points = 12;
  int view_width = 320;  ///< the live camera view (bigger than the policy's 64 x 64)
  int view_height = 240;
  /// The teacher's 3-D view on the Record screen (at most the scene's 640 x 480 buffer).
  int teacher_view_width = 480;
  int teacher_view_height = 360;
  /// A cell profile (devices/cell/cell_profile.h): teach with the real camera, beacons and UR5 it
  /// names instead of the simulated cell. Empty: the simulated cell.
  std::string cell_profile;
  /// A calibration file (recon calibrate --out) to attach to the session when it opens.
  std::string calibration_file;
  /// The program that shows the written report to the teacher, given its path (a desktop's
  /// opener, which starts the browser); "Open in browser" runs it.
  std::string open_command = "xdg-open";
  /// Where the Cell screen looks for plugged-in devices, and how often.
  std::string dev_dir = "/dev";
  std::vector<std::string> robot_hosts;  ///< UR controllers to list, "host[:port]"
  int device_scan_ms = 2000;
};

}  // namespace recon::studio
