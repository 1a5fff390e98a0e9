#pragma once

#include <array>

#include "ui/studio/studio_commands.h"
#include "ui/studio/studio_snapshot.h"
#include "ui/widgets/image_texture.h"

namespace recon::ui {

/// GL textures the screens draw with, and what the teacher is typing and keying; owned by the UI
/// thread for the window's life (per window, so two studios in one process never share a text
/// field).
struct StudioTextures {
  std::array<char, 1024> session_folder{};  ///< the session picker's folder field
  /// The teleop input the Record screen last sent: keys are compared with it, not with the
  /// snapshot's (which lags the commands), so a tap shorter than a round trip still stops.
  TeleopInput teleop_sent;
  ImageTexture camera;
  ImageTexture teacher_view;  ///< the Record screen's 3-D view
  ImageTexture play;
  ImageTexture rollout;
  ImageTexture rollout_other;  ///< the second method's frame, side by side
  ImageTexture episode;        ///< the Record screen's demonstration played back
};

/// What every screen gets: the frame's snapshot (read only) and where to put requests.
struct ScreenContext {
  const StudioSnapshot& snapshot;
  CommandQueue& commands;
  StudioTextures& textures;
};

// One function per workflow step (one file each), and the step list down the side.
void DrawSidebar(const ScreenContext& context);
void DrawCellScreen(const ScreenContext& context);
void DrawBeaconsScreen(const ScreenContext& context);
void DrawCalibrateScreen(const ScreenContext& context);
void DrawRecordScreen(const ScreenContext& context);
void DrawPlayScreen(const ScreenContext& context);
void DrawTrainScreen(const ScreenContext& context);
void DrawRolloutsScreen(const ScreenContext& context);
void DrawReportScreen(const ScreenContext& context);
/// The Rollouts step's trials on a real arm (a real cell's): trials_panel.cc.
void DrawTrialsPanel(const ScreenContext& context);
/// The Rollouts step's "Check what it looks at" panel (probe_panel.cc).
void DrawProbePanel(const ScreenContext& context);
/// Off / Gradient / Occlusion: the saliency over the frames played back (probe_panel.cc); what
/// the colours mean beside the buttons, or under them where the space is narrow. Within
/// `width` (0: the line's room), the buttons going under their title where it is narrower.
void DrawSaliencyToggle(const ScreenContext& context, bool hint_below = false, float width = 0);
/// The Record step's playback of a recorded demonstration with the saliency toggle, `width`
/// wide (episode_player.cc), in the live views' place.
void DrawEpisodePlayer(const ScreenContext& context, float width);
/// The Session menu of the menu bar (open, recent sessions) and the session picker page.
void DrawSessionMenu(const ScreenContext& context);
void DrawSessionPicker(const ScreenContext& context);

/// While the snapshot says the window's close button was pressed with something running: a
/// modal question, keep it running or stop it and close (AnswerClose). close_question.cc.
void DrawCloseQuestion(const ScreenContext& context);

/// What moves while play data records, as the Play data screen says it (play_screen.cc).
std::string PlayDataHowTo(const StudioSnapshot& snapshot);

/// The status of `step` in the snapshot.
const teach::StepStatus& StatusOf(const StudioSnapshot& snapshot, teach::Step step);
/// A blocked step's reason, for disabled buttons' tooltips (empty when not blocked).
std::string WhyBlocked(const StudioSnapshot& snapshot, teach::Step step);
bool Blocked(const StudioSnapshot& snapshot, teach::Step step);
/// For a step that moves the arm (Record, Play data, Rollouts): blocked by the workflow or by the
/// e-stop, and why (the e-stop's reason first).
bool MotionBlocked(const StudioSnapshot& snapshot, teach::Step step);
std::string WhyMotionBlocked(const StudioSnapshot& snapshot, teach::Step step);

}  // namespace recon::ui
