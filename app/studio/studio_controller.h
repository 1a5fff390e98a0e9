#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "ui/studio/studio_commands.h"
#include "ui/studio/studio_snapshot.h"

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
  int train_steps = 0;  ///< at most this many steps per method; 0: the world's recipe
  int rollout_tests = 10;
  int calibration_points = 12;
  int view_width = 320;  ///< the live camera view (bigger than the policy's 64 x 64)
  int view_height = 240;
  /// A cell profile (devices/cell/cell_profile.h): teach with the real camera, beacons and UR5 it
  /// names instead of the simulated cell. Empty: the simulated cell.
  std::string cell_profile;
  /// A calibration file (recon calibrate --out) to attach to the session when it opens.
  std::string calibration_file;
  /// Where the Cell screen looks for plugged-in devices, and how often.
  std::string dev_dir = "/dev";
  std::vector<std::string> robot_hosts;  ///< UR controllers to list, "host[:port]"
  int device_scan_ms = 2000;
};

/// The engine side of the studio: owns the session, the simulated cell and the workers, applies
/// the UI's commands and publishes snapshots. Two threads of its own: the cell thread (commands,
/// live camera, recording ticks) and the job thread (calibration, training, rollouts, report:
/// one at a time), so neither the window nor the camera freezes while a model trains. The UI
/// thread only calls Push and Snapshot.
class StudioController {
 public:
  /// Opens or creates the session; UserError naming what is wrong. The cell starts on its
  /// thread at once.
  explicit StudioController(const StudioOptions& options);
  ~StudioController();
  StudioController(const StudioController&) = delete;
  StudioController& operator=(const StudioController&) = delete;

  void Push(ui::StudioCommand command);
  /// The latest published state (a copy; cheap enough at 30 frames per second).
  ui::StudioSnapshot Snapshot() const;
  /// No command waiting, no recording and no job running.
  bool Idle() const;
  /// Every command pushed so far has been handled and a snapshot showing it published.
  bool Settled() const;

 private:
  class Cell;

  void RunCellThread();

  StudioOptions options_;
  ui::CommandQueue commands_;
  mutable std::mutex snapshot_mutex_;
  ui::StudioSnapshot snapshot_;
  std::atomic<bool> stop_{false};
  // Guarded by snapshot_mutex_, with snapshot_.
  bool published_busy_ = false;
  uint64_t pushed_ = 0;
  uint64_t handled_ = 0;
  std::unique_ptr<Cell> cell_;
  std::thread cell_thread_;
};

}  // namespace recon::studio
