#include <imgui.h>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

Status StateStatus(teach::StepState state) {
  switch (state) {
    case teach::StepState::kDone:
      return Status::kOk;
    case teach::StepState::kReady:
      return Status::kWarning;
    case teach::StepState::kBusy:
      return Status::kBusy;
    case teach::StepState::kBlocked:
      break;
  }
  return Status::kOff;
}

}  // namespace

const teach::StepStatus& StatusOf(const StudioSnapshot& snapshot, teach::Step step) {
  static const teach::StepStatus kUnknown;
  for (const teach::StepStatus& s : snapshot.steps) {
    if (s.step == step) return s;
  }
  return kUnknown;
}

std::string WhyBlocked(const StudioSnapshot& snapshot, teach::Step step) {
  return StatusOf(snapshot, step).why_blocked;
}

bool Blocked(const StudioSnapshot& snapshot, teach::Step step) {
  return StatusOf(snapshot, step).state == teach::StepState::kBlocked;
}

bool MotionBlocked(const StudioSnapshot& snapshot, teach::Step step) {
  return snapshot.safety.estop || Blocked(snapshot, step);
}

std::string WhyMotionBlocked(const StudioSnapshot& snapshot, teach::Step step) {
  if (snapshot.safety.estop) return "The e-stop is engaged: release it first.";
  return WhyBlocked(snapshot, step);
}

void DrawSidebar(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ImGui::SetWindowFontScale(1.2f);
  ImGui::TextUnformatted("RECON Studio");
  ImGui::SetWindowFontScale(1.0f);
  ImGui::TextDisabled("%s", s.session_open ? s.session_dir.c_str() : "no session open");
  ImGui::Separator();
  for (int i = 0; i < teach::kNumSteps; ++i) {
    const teach::Step step = teach::kAllSteps[i];
    const teach::StepStatus& status = StatusOf(s, step);
    ImGui::PushID(i);
    const bool selected = s.current_step == step;
    const bool can_open = s.can_open[i];
    const ImVec2 row = ImGui::GetCursorScreenPos();
    const std::string label = std::string(teach::StepTitle(step)) + "##step";
    // A two-line row: the step's title (the click target) and its summary below.
    if (Selectable(label.c_str(), selected, can_open) && !selected) {
      context.commands.Push(OpenStep{step});
    }
    if (!can_open && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled) &&
        !status.why_blocked.empty()) {
      ImGui::SetTooltip("%s", status.why_blocked.c_str());
    }
    const float right = row.x + ImGui::GetContentRegionAvail().x;
    if (step == s.next_step && !selected) {
      ImGui::SetCursorScreenPos(ImVec2(right - Px(64), row.y));
      ImGui::TextColored(ImVec4(0.0f, 0.447f, 0.698f, 1.0f), "next");
    }
    ImGui::SetCursorScreenPos(ImVec2(right - Px(18), row.y));
    StatusText(StateStatus(status.state), "");
    ImGui::SetCursorScreenPos(
        ImVec2(row.x + Px(12), row.y + ImGui::GetTextLineHeightWithSpacing()));
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + ImGui::GetContentRegionAvail().x - 4);
    ImGui::TextWrapped("%s", status.state == teach::StepState::kBlocked ? status.why_blocked.c_str()
                                                                        : status.summary.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
    ImGui::Spacing();
    ImGui::PopID();
  }
}

}  // namespace recon::ui
