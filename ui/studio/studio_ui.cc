#include "ui/studio/studio_ui.h"

#include <imgui.h>

#include <cfloat>
#include <string>

#include "ui/platform/frame_input.h"
#include "ui/widgets/widget_registry.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

constexpr float kSidebarWidth = 270.0f;
constexpr float kStatusHeight = 30.0f;
constexpr ImGuiWindowFlags kPanel = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                    ImGuiWindowFlags_NoSavedSettings |
                                    ImGuiWindowFlags_NoBringToFrontOnFocus;
// The step list and the step's screen scroll, with a scrollbar in view, where a window (or a
// step's results) is taller than the room: nothing is cut off out of sight.
constexpr ImGuiWindowFlags kScrollingPanel =
    ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
    ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_HorizontalScrollbar;

/// A new step's screen starts at its top, not where the last one was scrolled to.
void ScrollToTopOnNewStep(const StudioSnapshot& snapshot) {
  ImGuiStorage* storage = ImGui::GetStateStorage();
  const ImGuiID id = ImGui::GetID("shown-step");
  const int shown = (snapshot.picking_session || !snapshot.session_open)
                        ? -1
                        : static_cast<int>(snapshot.current_step);
  if (storage->GetInt(id, -2) != shown) ImGui::SetScrollY(0.0f);
  storage->SetInt(id, shown);
}

/// What a window smaller than the studio's smallest layout says, or "" when it is not: the
/// panels scroll, so nothing is lost, but the person should know why they must.
std::string WindowTooSmall(const ImVec2& display) {
  const float width = Px(static_cast<float>(kMinWindowWidth));
  const float height = Px(static_cast<float>(kMinWindowHeight));
  if (display.x >= width - 0.5f && display.y >= height - 0.5f) return "";
  // Short: it shares the line with the e-stop button in the narrowest of windows.
  return Format("Window smaller than %.0f x %.0f: scroll to see all", width, height);
}

void DrawScreen(const ScreenContext& context) {
  if (context.snapshot.picking_session || !context.snapshot.session_open) {
    return DrawSessionPicker(context);
  }
  switch (context.snapshot.current_step) {
    case teach::Step::kCell:
      return DrawCellScreen(context);
    case teach::Step::kBeacons:
      return DrawBeaconsScreen(context);
    case teach::Step::kCalibrate:
      return DrawCalibrateScreen(context);
    case teach::Step::kRecord:
      return DrawRecordScreen(context);
    case teach::Step::kPlay:
      return DrawPlayScreen(context);
    case teach::Step::kTrain:
      return DrawTrainScreen(context);
    case teach::Step::kRollouts:
      return DrawRolloutsScreen(context);
    case teach::Step::kReport:
      return DrawReportScreen(context);
  }
}

/// The bottom line: what is happening, and the e-stop, always within reach. F12 engages it from
/// anywhere (even while typing: stopping the arm comes first); Escape only closes menus.
void DrawStatusBar(const StudioSnapshot& snapshot, CommandQueue& commands) {
  const SafetyView& safety = snapshot.safety;
  const bool key = ImGui::IsKeyPressed(kEmergencyStopKey, false);
  if (key && !safety.estop) commands.Push(EmergencyStop{true, "F12 pressed"});
  const std::string too_small = WindowTooSmall(ImGui::GetIO().DisplaySize);
  if (safety.estop) {
    ImGui::TextColored(ImVec4(0.8f, 0.0f, 0.0f, 1.0f), "E-STOP ENGAGED (%s): the arm is stopped.",
                       safety.estop_reason.c_str());
  } else if (!too_small.empty()) {
    ImGui::BeginGroup();
    StatusText(Status::kWarning, too_small);
    ImGui::EndGroup();
    WidgetRegistry::ForThisThread().AddLastRegion("window-too-small");
  } else {
    ImGui::TextUnformatted(snapshot.status.empty() ? "Ready." : snapshot.status.c_str());
  }
  constexpr float kButtonWidth = 150.0f;
  ImGui::SameLine(ImGui::GetWindowWidth() - Px(kButtonWidth) - Px(10));
  ImGui::SetCursorPosY(Px(2));
  ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.8f, 0.05f, 0.05f, 1.0f));
  ImGui::PushStyleColor(ImGuiCol_ButtonHovered, ImVec4(0.9f, 0.15f, 0.1f, 1.0f));
  ImGui::PushStyleColor(ImGuiCol_ButtonActive, ImVec4(0.6f, 0.0f, 0.0f, 1.0f));
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 1, 1, 1));
  if (safety.estop) {
    if (Button("Release e-stop")) commands.Push(EmergencyStop{false, ""});
  } else if (Button("E-STOP (F12)")) {
    commands.Push(EmergencyStop{true, "e-stop button"});
  }
  ImGui::PopStyleColor(4);
}

}  // namespace

/// The errors shown until dismissed, in a panel over the bottom of the screen (its lower-left
/// corner at `bottom_left`, `width` wide) rather than above it: an error arriving while the
/// teacher works pushes nothing down under the pointer.
void DrawErrors(const StudioSnapshot& snapshot, CommandQueue& commands, ImVec2 bottom_left,
                float width) {
  if (snapshot.errors.empty()) return;
  ImGui::SetNextWindowPos(bottom_left, ImGuiCond_Always, ImVec2(0.0f, 1.0f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0), ImVec2(width, FLT_MAX));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(1.0f, 0.93f, 0.92f, 1.0f));
  ImGui::Begin("Errors", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::PushTextWrapPos(width - Px(16));
  for (const std::string& error : snapshot.errors) StatusText(Status::kError, error);
  ImGui::PopTextWrapPos();
  if (Button("Dismiss")) commands.Push(DismissErrors{});
  ImGui::End();
  ImGui::PopStyleColor();
}

void DrawStudio(const StudioSnapshot& snapshot, CommandQueue& commands, StudioTextures& textures) {
  // While a demonstration records, the arrows and Space drive the arm: they must not also move
  // ImGui's keyboard focus and press whatever button it lands on (from the next frame on).
  ImGuiIO& io = ImGui::GetIO();
  if (snapshot.recording) {
    io.ConfigFlags &= ~ImGuiConfigFlags_NavEnableKeyboard;
  } else {
    io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard;
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const ScreenContext context{snapshot, commands, textures};
  float top = 0;
  if (ImGui::BeginMainMenuBar()) {
    DrawSessionMenu(context);
    if (snapshot.session_open) {
      ImGui::SameLine(0, 30);
      ImGui::TextDisabled("%s", snapshot.session_dir.c_str());
    }
    top = ImGui::GetWindowSize().y;
    ImGui::EndMainMenuBar();
  }
  const float body = display.y - Px(kStatusHeight) - top;

  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(Px(kSidebarWidth), body));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.93f, 0.94f, 0.955f, 1.0f));
  ImGui::Begin("Steps", nullptr, kScrollingPanel & ~ImGuiWindowFlags_HorizontalScrollbar);
  DrawSidebar(context);
  ImGui::End();
  ImGui::PopStyleColor();

  ImGui::SetNextWindowPos(ImVec2(Px(kSidebarWidth), top));
  ImGui::SetNextWindowSize(ImVec2(display.x - Px(kSidebarWidth), body));
  // Narrower than the smallest layout: the screen keeps that layout and scrolls sideways,
  // rather than squeezing its columns until they overflow. The screens size their panels by
  // the room they see (GetContentRegionAvail), so they are drawn in a child as wide as the
  // smallest layout's screen, which scrolls up and down itself; the window scrolls it sideways.
  const float min_content = Px(static_cast<float>(kMinWindowWidth) - kSidebarWidth) -
                            2 * ImGui::GetStyle().WindowPadding.x;
  const bool narrow = display.x < Px(static_cast<float>(kMinWindowWidth));
  ImGui::Begin("Screen", nullptr, kScrollingPanel);
  if (narrow) {
    // Padded as the screen is, so that its content has the smallest layout's room; without a
    // horizontal scrollbar of its own, as with one the room a child reports grows with what it
    // drew last and its panels widen past it.
    ImGui::BeginChild("smallest-layout",
                      ImVec2(min_content + 2 * ImGui::GetStyle().WindowPadding.x, 0), false,
                      ImGuiWindowFlags_AlwaysUseWindowPadding);
  }
  ScrollToTopOnNewStep(snapshot);
  DrawScreen(context);
  if (narrow) ImGui::EndChild();
  ImGui::End();
  DrawErrors(snapshot, commands, ImVec2(Px(kSidebarWidth), top + body),
             display.x - Px(kSidebarWidth));

  ImGui::SetNextWindowPos(ImVec2(0, top + body));
  ImGui::SetNextWindowSize(ImVec2(display.x, Px(kStatusHeight)));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(Px(10), Px(5)));
  // Exactly its height: the style's smallest window (32 px) would hang it off the window's edge.
  ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1, 1));
  ImGui::Begin("Status", nullptr, kPanel);
  DrawStatusBar(snapshot, commands);
  ImGui::End();
  ImGui::PopStyleVar(2);
  DrawCloseQuestion(context);
}

}  // namespace recon::ui
