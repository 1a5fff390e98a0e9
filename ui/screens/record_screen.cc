#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "ui/screens/grip_readout.h"
#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/height_gauge.h"
#include "ui/widgets/orbit_view.h"
#include "ui/widgets/widget_registry.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

// The live view's width at most; narrower windows get a narrower view, so the episode list keeps
// its columns (from 1024 x 640 up).
constexpr float kCameraWidth = 420.0f;
// Beside the teacher's 3-D view the robot's camera is a thumbnail: the teacher steers by the
// 3-D view, and sees here what the policy will see.
constexpr float kThumbnailWidth = 112.0f;

// What the right column (the take's buttons, the list of demonstrations) needs beside the views.
constexpr float kRightColumnWidth = 620.0f;

float CameraWidth() { return GrowingViewWidth(0.45f, Px(240), Px(kCameraWidth)); }

/// The teacher's 3-D view grows with the window: all the width the right column leaves (a third
/// of it at least), as long as the readout and the keys under it stay in view.
float TeacherViewWidth() {
  const float room = ImGui::GetContentRegionAvail().x;
  const float by_room =
      std::max(room * 0.34f, room - Px(kThumbnailWidth + 16) - Px(kRightColumnWidth));
  const float by_height = (ImGui::GetWindowHeight() - Px(420)) * 4.0f / 3.0f;
  return std::max(Px(240), std::min(by_room, by_height));
}

/// The episode list's buttons, Delete, Re-record and Bad (or Good), side by side.
float EpisodeButtonsWidth() {
  const ImGuiStyle& style = ImGui::GetStyle();
  return ImGui::CalcTextSize("Delete").x + ImGui::CalcTextSize("Re-record").x +
         std::max(ImGui::CalcTextSize("Good").x, ImGui::CalcTextSize("Bad").x) +
         6 * style.FramePadding.x + 2 * style.ItemSpacing.x;
}

bool KeyDown(ImGuiKey key) { return ImGui::IsKeyDown(ImGui::GetKeyIndex(key)); }
bool KeyPressed(ImGuiKey key) { return ImGui::IsKeyPressed(ImGui::GetKeyIndex(key), false); }

/// The keyboard teleop: while a demonstration records, the arrows drive the arm as it moves on
/// screen (in the 3-D view where there is one), Page Up / Page Down raise and lower it, Space opens
/// or closes the gripper and Enter keeps the demonstration. Sends the controller a TeleopInput when
/// the keys change.
void ReadTeleopKeys(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  TeleopInput& sent = context.textures.teleop_sent;
  if (!s.recording || s.teleop != TeleopMode::kKeyboard || ImGui::GetIO().WantTextInput) {
    sent = {};  // the controller stops the arm between takes
    return;
  }
  TeleopInput input;
  input.screen_right =
      static_cast<float>(KeyDown(ImGuiKey_RightArrow) - KeyDown(ImGuiKey_LeftArrow));
  input.screen_up = static_cast<float>(KeyDown(ImGuiKey_UpArrow) - KeyDown(ImGuiKey_DownArrow));
  input.raise = static_cast<float>(KeyDown(ImGuiKey_PageUp) - KeyDown(ImGuiKey_PageDown));
  input.turn = static_cast<float>(KeyDown(ImGuiKey_Home) - KeyDown(ImGuiKey_End));
  if (input != sent) {
    context.commands.Push(input);
    sent = input;
  }
  if (KeyPressed(ImGuiKey_Space)) context.commands.Push(ToggleGripper{});
  if (KeyPressed(ImGuiKey_Enter) || KeyPressed(ImGuiKey_KeyPadEnter)) {
    context.commands.Push(StopRecording{});
  }
}

/// One row of the key legend: the key, and what it does.
void LegendRow(const char* keys, const char* action) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(keys);
  ImGui::TableNextColumn();
  ImGui::TextDisabled("%s", action);
}

/// What each key or stick does in the chosen teleop, on screen while teaching.
void DrawMappings(const StudioSnapshot& s) {
  if (s.teleop == TeleopMode::kScripted) {
    ImGui::TextDisabled("The scripted teacher demonstrates. Pick Keyboard or Gamepad to teach.");
    return;
  }
  const char* seen =
      s.teacher_view.available ? "as the 3-D view shows it" : "as the camera shows it";
  if (!ImGui::BeginTable("mappings", 2, ImGuiTableFlags_SizingFixedFit)) return;
  if (s.teleop == TeleopMode::kKeyboard) {
    LegendRow("Arrows", Format("move the arm %s (a tap: 3 mm)", seen).c_str());
    LegendRow("Page Up / Down", "raise / lower it (held: faster)");
    LegendRow("Home / End", "turn the wrist (cyan: the jaw's axis)");
    LegendRow("Space", "close / open the gripper");
    LegendRow("Enter", "keep the take");
  } else {
    LegendRow("Left stick", Format("move the arm %s", seen).c_str());
    LegendRow("Right stick", "up / down: raise / lower it; sideways: turn the wrist");
    LegendRow("A", "close / open the gripper");
    LegendRow("Start", "keep the take");
  }
  LegendRow("F12", "emergency stop");
  ImGui::EndTable();
}

/// How wide the teleop row is with every choice marked: the same whichever is chosen.
float TeleopRowWidth(const StudioSnapshot& s) {
  const ImGuiStyle& style = ImGui::GetStyle();
  float width = 0;
  for (const TeleopChoice& choice : s.teleop_choices) {
    width += (width > 0 ? style.ItemSpacing.x : 0) +
             ImGui::CalcTextSize((std::string("[x] ") + TeleopModeLabel(choice.mode)).c_str()).x +
             2 * style.FramePadding.x;
  }
  return width;
}

void DrawTeleopChoice(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ImGui::TextUnformatted("Who drives the arm in the next take:");
  bool first = true;
  for (const TeleopChoice& choice : s.teleop_choices) {
    if (!first) ImGui::SameLine();
    first = false;
    const bool enabled = choice.available && !s.recording;
    const std::string label =
        (choice.mode == s.teleop ? "[x] " : "[ ] ") + std::string(TeleopModeLabel(choice.mode));
    if (Button((label + "##teleop").c_str(), enabled,
               choice.available ? "finish the recording first" : choice.why_not)) {
      context.commands.Push(SetTeleopMode{choice.mode});
    }
  }
  DrawMappings(s);
}

/// The grip's readout (ReadGrip): four lines whatever the state, so what is drawn under them
/// never moves.
void DrawGripState(const StudioSnapshot& s) {
  const GripReadout readout = ReadGrip(s);
  StatusText(readout.status, readout.state);
  ImGui::TextUnformatted(readout.height.c_str());
  ImGui::TextUnformatted(readout.hint.c_str());
  if (readout.wrist.empty()) {
    ImGui::TextUnformatted("");
  } else if (readout.wrist_status == Status::kWarning) {
    StatusText(readout.wrist_status, readout.wrist);
  } else {
    ImGui::TextDisabled("%s", readout.wrist.c_str());
  }
}

/// The teacher's 3-D view with the robot's camera and the height gauge beside it, its preset
/// views under it, and the grip's readout.
void DrawTeacherView(const ScreenContext& context, float width) {
  const StudioSnapshot& s = context.snapshot;
  context.textures.teacher_view.Update(s.teacher_view.image, s.teacher_view.frame);
  ImGui::BeginGroup();
  if (auto moved =
          OrbitView("teacher-view", context.textures.teacher_view, width, s.teacher_view)) {
    context.commands.Push(*moved);
  }
  if (auto preset = OrbitPresets(s.teacher_view, width)) context.commands.Push(*preset);
  ImGui::EndGroup();
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::TextDisabled("Robot's camera");
  // No beacon labels on a thumbnail: they would cover it (the Beacons screen shows them).
  const ImVec2 thumbnail = ImGui::GetCursorScreenPos();
  CameraView("camera##record", context.textures.camera, Px(kThumbnailWidth), {}, {});
  // The jaw's axis as the robot's camera sees it, from above: the line a grasp closes along.
  const std::array<float, 4>& jaw = s.jaw_camera_pixels;
  if (context.textures.camera.width() > 0 && (jaw[0] != jaw[2] || jaw[1] != jaw[3])) {
    const float scale = Px(kThumbnailWidth) / static_cast<float>(context.textures.camera.width());
    ImGui::GetWindowDrawList()->AddLine(
        ImVec2(thumbnail.x + jaw[0] * scale, thumbnail.y + jaw[1] * scale),
        ImVec2(thumbnail.x + jaw[2] * scale, thumbnail.y + jaw[3] * scale),
        IM_COL32(30, 215, 240, 235), Px(2));
  }
  HeightGauge("height-gauge", s.grip_m[2], s.grip.grasp_min_m, s.grip.grasp_max_m,
              std::max(Px(90), 0.75f * width - Px(kThumbnailWidth) * 0.75f - Px(64)));
  ImGui::EndGroup();
  DrawGripState(s);
}

/// The take's buttons and what the take is doing, in a block of one size whatever the take's
/// state, each button always in its place (enabled when it applies): a click aimed at one as a
/// take starts or ends never lands on another, and the episode list below never moves.
void DrawTakeControls(const ScreenContext& context, bool blocked, const std::string& why) {
  const StudioSnapshot& s = context.snapshot;
  const bool pending = !s.pending_take.empty();
  const bool counting = s.recording && (s.countdown_s > 0 || s.take_homing);
  const float width = std::min(Px(520), ImGui::GetContentRegionAvail().x);
  const ImGuiStyle& style = ImGui::GetStyle();
  // One width for both labels of the second button, so Discard stays where it is.
  const float keep_width =
      ImGui::CalcTextSize("Keep as not done").x + 2 * ImGui::GetStyle().FramePadding.x;
  // Discard goes under the others where the column is too narrow for the three (a window's
  // size, not the take's state, decides).
  const float row = ImGui::CalcTextSize("Start recording").x + keep_width +
                    ImGui::CalcTextSize("Discard").x + 4 * style.FramePadding.x +
                    2 * style.ItemSpacing.x;
  const bool one_row = row <= width;
  // As high as its tallest state needs (a take's last seconds: its line, the bar, the warning,
  // each line wrapped once in a narrow column), whatever state it is in.
  const float height = (one_row ? 1 : 2) * ImGui::GetFrameHeightWithSpacing() +
                       (width < Px(500) ? 5 : 3) * ImGui::GetTextLineHeightWithSpacing() +
                       ImGui::GetFrameHeightWithSpacing();
  ImGui::PushStyleColor(ImGuiCol_ChildBg, ImVec4(0, 0, 0, 0));
  ImGui::BeginChild("take-controls", ImVec2(width, height), false,
                    ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  const bool take = s.recording || pending;
  if (Button("Start recording", !take && !blocked, take ? "finish the take first" : why)) {
    context.commands.Push(StartRecording{});
  }
  ImGui::SameLine();
  // A take that ended unfinished waits for the teacher: nothing is kept or lost unasked.
  if (Button(pending ? "Keep as not done##take" : "Stop and keep##take",
             pending || (s.recording && !counting),
             counting ? "the take has not started" : "no take is running", keep_width)) {
    context.commands.Push(StopRecording{});
  }
  if (one_row) ImGui::SameLine();
  if (Button("Discard##take", take, "no take is running")) {
    context.commands.Push(DiscardRecording{});
  }
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width - style.WindowPadding.x);
  if (pending) {
    StatusText(Status::kWarning, s.pending_take + ".");
  } else if (counting && s.countdown_s <= 0) {
    StatusText(Status::kBusy, "The arm returns to its home pose; the take starts when it is there");
  } else if (counting) {
    StatusText(Status::kBusy,
               Format("Get ready: the take starts in %.0f s%s", std::ceil(s.countdown_s),
                      s.take_homing ? " (the arm returns home meanwhile)" : ""));
  } else if (s.recording) {
    // The time limit in view, and a warning before it ends the take.
    const double elapsed = s.recording_samples * s.recording_step_s;
    const double limit = s.recording_max_samples * s.recording_step_s;
    StatusText(Status::kBusy, Format("Recording: %d samples, %.1f s of %.0f s", s.recording_samples,
                                     elapsed, limit));
    ImGui::ProgressBar(limit > 0 ? static_cast<float>(elapsed / limit) : 0.0f, ImVec2(width, 0),
                       "");
    if (s.teleop != TeleopMode::kScripted && limit > 0 && limit - elapsed <= 5.0) {
      StatusText(Status::kWarning,
                 Format("%.0f s left: the take ends at %.0f s (then keep or discard it)",
                        std::max(0.0, limit - elapsed), limit));
    }
  } else if (blocked && !why.empty()) {
    ImGui::TextWrapped("%s", why.c_str());
  }
  ImGui::PopTextWrapPos();
  ImGui::EndChild();
  ImGui::PopStyleColor();
}

}  // namespace

void DrawRecordScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Record", teach::StepPurpose(teach::Step::kRecord));
  const bool blocked = MotionBlocked(s, teach::Step::kRecord) && !s.recording;
  const std::string why = WhyMotionBlocked(s, teach::Step::kRecord);
  ReadTeleopKeys(context);
  context.textures.camera.Update(s.camera, s.camera_frame);
  const float start_x = ImGui::GetCursorPosX();
  ImGui::BeginGroup();
  float left_width = 0;
  const float views_width =
      s.teacher_view.available ? TeacherViewWidth() + Px(kThumbnailWidth + 16) : CameraWidth();
  if (!s.episode_playback.episode.empty() && !s.recording) {
    // A demonstration played back takes the live views' place until it is closed.
    left_width = views_width;
    DrawEpisodePlayer(context, left_width);
  } else if (s.teacher_view.available) {
    left_width = views_width;
    DrawTeacherView(context, TeacherViewWidth());
  } else {
    left_width = CameraWidth();
    CameraView("camera##record", context.textures.camera, left_width, s.beacons, {});
    DrawGripState(s);
  }
  left_width = std::max(left_width, TeleopRowWidth(s));
  ImGui::PushTextWrapPos(start_x + left_width);
  DrawTeleopChoice(context);
  // The parts, so 4.6 s before the first take reads as what it is (placing the beacons).
  ImGui::TextWrapped("Teacher's time so far: %.1f s (kept takes %.1f s)", s.teacher_seconds,
                     s.teacher_demo_seconds);
  // Not kept: the takes discarded or recorded over, and the waits before a person's takes (the
  // countdown, or the arm's way home when longer).
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("unkept %.1f s (%d takes, countdowns), play %.1f s, beacons %.1f s",
                     s.teacher_discarded_seconds + s.teacher_countdown_seconds,
                     s.teacher_discarded_takes, s.teacher_play_seconds,
                     s.teacher_placement_seconds);
  ImGui::PopStyleColor();
  ImGui::PopTextWrapPos();
  ImGui::EndGroup();
  // The columns are regions: text running out of one into the other is a layout fault.
  WidgetRegistry::ForThisThread().AddLastRegion("record:views-column");
  // The right side starts at one place whatever the left side shows (a teleop chosen, a take).
  ImGui::SameLine(start_x + left_width + ImGui::GetStyle().ItemSpacing.x);
  ImGui::BeginGroup();
  DrawTakeControls(context, blocked, why);
  ImGui::Spacing();
  ImGui::Text("Demonstrations (%zu)", s.episodes.size());
  const std::string undo_label = "Undo delete " + s.undo_delete;
  const float undo_width =
      ImGui::CalcTextSize(undo_label.c_str()).x + 2 * ImGui::GetStyle().FramePadding.x;
  const float hint_width = ImGui::CalcTextSize("click one to watch it").x;
  // The hint gives way to Undo where the line has no room for both: the list never moves down.
  if (s.undo_delete.empty() || ImGui::GetContentRegionAvail().x - ImGui::GetItemRectSize().x >
                                   hint_width + undo_width + 3 * ImGui::GetStyle().ItemSpacing.x) {
    ImGui::SameLine();
    ImGui::TextDisabled("click one to watch it");
  }
  if (!s.undo_delete.empty()) {
    ImGui::SameLine();
    // Enabled exactly when the controller takes it (StudioCell::RequireIdle).
    const bool idle = !s.recording && s.pending_take.empty() && s.busy_with.empty();
    if (Button((undo_label + "##undo-delete").c_str(), idle,
               s.busy_with.empty() ? std::string("finish the take first")
                                   : "wait for " + s.busy_with + " to end")) {
      context.commands.Push(UndoDelete{});
    }
  }
  // As wide as its columns (a row is one click target: none beyond them), or the room left.
  const float columns[] = {Px(104), Px(62), Px(52), Px(42), EpisodeButtonsWidth()};
  float table_width = ImGui::GetStyle().ScrollbarSize + Px(2);
  for (float column : columns) table_width += column + 2 * ImGui::GetStyle().CellPadding.x + 1;
  if (ImGui::BeginTable("episodes", 5,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                            ImGuiTableFlags_ScrollX,
                        ImVec2(std::min(table_width, ImGui::GetContentRegionAvail().x), Px(320)))) {
    ImGui::TableSetupColumn("Episode", ImGuiTableColumnFlags_WidthFixed, columns[0]);
    ImGui::TableSetupColumn("Samples", ImGuiTableColumnFlags_WidthFixed, columns[1]);
    ImGui::TableSetupColumn("Time", ImGuiTableColumnFlags_WidthFixed, columns[2]);
    ImGui::TableSetupColumn("Done", ImGuiTableColumnFlags_WidthFixed, columns[3]);
    // Fixed widths: a narrow window scrolls the table sideways instead of clipping its buttons.
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, columns[4]);
    ImGui::TableHeadersRow();
    for (const EpisodeView& e : s.episodes) {
      ImGui::PushID(e.name.c_str());
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      // The row plays the demonstration back (in the live views' place) when clicked anywhere
      // but on its buttons.
      const bool shown = s.episode_playback.episode == e.name;
      if (e.bad)
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
      if (SelectableRow((e.name + (e.bad ? " (bad)" : "") + "##watch").c_str(), shown,
                        e.problem.empty()) &&
          !shown) {
        context.commands.Push(ShowEpisodeFrame{e.name, 0, s.episode_playback.method});
      }
      if (e.bad) ImGui::PopStyleColor();
      ImGui::TableNextColumn();
      ImGui::Text("%d", e.samples);
      ImGui::TableNextColumn();
      ImGui::Text("%.1f s", e.seconds);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(!e.problem.empty() ? "damaged" : e.succeeded ? "yes" : "no");
      ImGui::TableNextColumn();
      const bool idle = !s.recording && !blocked && s.pending_take.empty();
      if (Button(("Delete##" + e.name).c_str(), idle)) {
        context.commands.Push(DeleteEpisode{e.name});
      }
      ImGui::SameLine();
      if (Button(("Re-record##" + e.name).c_str(), idle)) {
        context.commands.Push(ReRecordEpisode{e.name});
      }
      ImGui::SameLine();
      if (Button((std::string(e.bad ? "Good" : "Bad") + "##" + e.name).c_str(), idle)) {
        context.commands.Push(MarkEpisodeBad{e.name, !e.bad});
      }
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  ImGui::EndGroup();
  WidgetRegistry::ForThisThread().AddLastRegion("record:take-column");
}

}  // namespace recon::ui
