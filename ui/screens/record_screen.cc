#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

// The live view's width at most; narrower windows get a narrower view, so the episode list keeps
// its columns (from 1024 x 640 up).
constexpr float kCameraWidth = 420.0f;

float CameraWidth() {
  return std::clamp(ImGui::GetContentRegionAvail().x * 0.45f, Px(240), Px(kCameraWidth));
}

bool KeyDown(ImGuiKey key) { return ImGui::IsKeyDown(ImGui::GetKeyIndex(key)); }
bool KeyPressed(ImGuiKey key) { return ImGui::IsKeyPressed(ImGui::GetKeyIndex(key), false); }

/// The keyboard teleop: while a demonstration records, the arrows drive the arm as it moves on
/// screen, Page Up / Page Down raise and lower it, Space opens or closes the gripper and Enter
/// keeps the demonstration. Sends the controller a TeleopInput when the keys change.
void ReadTeleopKeys(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  if (!s.recording || s.teleop != TeleopMode::kKeyboard || ImGui::GetIO().WantTextInput) return;
  TeleopInput input;
  input.screen_right =
      static_cast<float>(KeyDown(ImGuiKey_RightArrow) - KeyDown(ImGuiKey_LeftArrow));
  input.screen_up = static_cast<float>(KeyDown(ImGuiKey_UpArrow) - KeyDown(ImGuiKey_DownArrow));
  input.raise = static_cast<float>(KeyDown(ImGuiKey_PageUp) - KeyDown(ImGuiKey_PageDown));
  input.close_gripper = s.teleop_input.close_gripper != KeyPressed(ImGuiKey_Space);
  if (input != s.teleop_input) context.commands.Push(input);
  if (KeyPressed(ImGuiKey_Enter) || KeyPressed(ImGuiKey_KeyPadEnter)) {
    context.commands.Push(StopRecording{});
  }
}

void DrawTeleopChoice(const ScreenContext& context, float width) {
  const StudioSnapshot& s = context.snapshot;
  ImGui::TextUnformatted("Teleop:");
  for (const TeleopChoice& choice : s.teleop_choices) {
    ImGui::SameLine();
    const bool enabled = choice.available && !s.recording;
    const std::string label =
        (choice.mode == s.teleop ? "[x] " : "[ ] ") + std::string(TeleopModeLabel(choice.mode));
    if (Button((label + "##teleop").c_str(), enabled,
               choice.available ? "finish the recording first" : choice.why_not)) {
      context.commands.Push(SetTeleopMode{choice.mode});
    }
  }
  const char* help = s.teleop == TeleopMode::kKeyboard
                         ? "Arrows move the arm as on screen, Page Up/Down raise and lower it, "
                           "Space opens or closes the gripper, Enter keeps the demonstration."
                     : s.teleop == TeleopMode::kGamepad
                         ? "The left stick moves the arm as on screen, the right stick raises "
                           "and lowers it, A opens or closes the gripper, Start keeps the "
                           "demonstration."
                         : nullptr;
  if (help != nullptr) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", help);
    ImGui::PopStyleColor();
    ImGui::PopTextWrapPos();
  }
}

}  // namespace

void DrawRecordScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Record", teach::StepPurpose(teach::Step::kRecord));
  const bool blocked = MotionBlocked(s, teach::Step::kRecord) && !s.recording;
  const std::string why = WhyMotionBlocked(s, teach::Step::kRecord);
  ReadTeleopKeys(context);
  context.textures.camera.Update(s.camera, s.camera_frame);
  ImGui::BeginGroup();
  const float camera_width = CameraWidth();
  CameraView("camera##record", context.textures.camera, camera_width, s.beacons, {});
  DrawTeleopChoice(context, camera_width);
  ImGui::Text("Grip at (%.2f, %.2f, %.2f) m, gripper %s", s.grip_m[0], s.grip_m[1], s.grip_m[2],
              s.gripper_closed ? "closed" : "open");
  // The parts, so 4.6 s before the first take reads as what it is (placing the beacons).
  ImGui::Text("Teacher's time so far: %.1f s", s.teacher_seconds);
  ImGui::TextDisabled("demonstrations %.1f s, play %.1f s, placing beacons %.1f s",
                      s.teacher_demo_seconds, s.teacher_play_seconds, s.teacher_placement_seconds);
  ImGui::EndGroup();
  ImGui::SameLine();
  ImGui::BeginGroup();
  if (!s.pending_take.empty()) {
    // A take that ended unfinished waits for the teacher: nothing is kept or lost unasked.
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + Px(520));
    StatusText(Status::kWarning, s.pending_take + ".");
    ImGui::PopTextWrapPos();
    if (Button("Keep as not done")) context.commands.Push(StopRecording{});
    ImGui::SameLine();
    if (Button("Discard##pending")) context.commands.Push(DiscardRecording{});
  } else if (s.recording && s.countdown_s > 0) {
    StatusText(Status::kBusy,
               Format("Get ready: the take starts in %.0f s", std::ceil(s.countdown_s)));
    if (Button("Discard")) context.commands.Push(DiscardRecording{});
  } else if (s.recording) {
    // The time limit in view, and a warning before it ends the take.
    const double elapsed = s.recording_samples * s.recording_step_s;
    const double limit = s.recording_max_samples * s.recording_step_s;
    StatusText(Status::kBusy, Format("Recording: %d samples, %.1f s of %.0f s", s.recording_samples,
                                     elapsed, limit));
    ImGui::ProgressBar(limit > 0 ? static_cast<float>(elapsed / limit) : 0.0f, ImVec2(Px(520), 0),
                       "");
    if (s.teleop != TeleopMode::kScripted && limit > 0 && limit - elapsed <= 5.0) {
      StatusText(Status::kWarning,
                 Format("%.0f s left: the take ends at %.0f s (then keep or discard it)",
                        std::max(0.0, limit - elapsed), limit));
    }
    if (Button("Stop and keep")) context.commands.Push(StopRecording{});
    ImGui::SameLine();
    if (Button("Discard")) context.commands.Push(DiscardRecording{});
  } else if (Button("Start recording", !blocked, why)) {
    context.commands.Push(StartRecording{});
  }
  if (blocked && !why.empty()) ImGui::TextWrapped("%s", why.c_str());
  ImGui::Spacing();
  ImGui::Text("Demonstrations (%zu)", s.episodes.size());
  if (!s.undo_delete.empty()) {
    ImGui::SameLine();
    if (Button(("Undo delete " + s.undo_delete + "##undo-delete").c_str(),
               !s.recording && s.pending_take.empty(), "finish the take first")) {
      context.commands.Push(UndoDelete{});
    }
  }
  if (ImGui::BeginTable("episodes", 5,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                            ImGuiTableFlags_ScrollX,
                        ImVec2(0, Px(320)))) {
    ImGui::TableSetupColumn("Episode", ImGuiTableColumnFlags_WidthFixed, Px(120));
    ImGui::TableSetupColumn("Samples", ImGuiTableColumnFlags_WidthFixed, Px(64));
    ImGui::TableSetupColumn("Time", ImGuiTableColumnFlags_WidthFixed, Px(60));
    ImGui::TableSetupColumn("Done", ImGuiTableColumnFlags_WidthFixed, Px(40));
    // Fixed widths: a narrow window scrolls the table sideways instead of clipping its buttons.
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed, Px(240));
    ImGui::TableHeadersRow();
    for (const EpisodeView& e : s.episodes) {
      ImGui::PushID(e.name.c_str());
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      if (e.bad) {
        ImGui::TextDisabled("%s (bad)", e.name.c_str());
      } else {
        ImGui::TextUnformatted(e.name.c_str());
      }
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
}

}  // namespace recon::ui
