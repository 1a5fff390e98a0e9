#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/studio/studio_config.h"
#include "ui/studio/studio_commands.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

class StudioCell;

/// The engine side of the studio: owns the session, the cell (StudioCell) and the workers, applies
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
  /// A pass of the cell loop has run at the studio's time `t` or later (StudioOptions::clock),
  /// and the snapshot shows it if one was due.
  bool CaughtUp(std::chrono::steady_clock::time_point t) const;

 private:
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
  std::chrono::steady_clock::time_point passed_{};  ///< the time of the last finished pass
  std::unique_ptr<StudioCell> cell_;
  std::thread cell_thread_;
};

}  // namespace recon::studio
