#include "ui/studio/studio_ui.h"

#include <imgui.h>

#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

constexpr float kSidebarWidth = 270.0f;
constexpr float kStatusHeight = 30.0f;
constexpr ImGuiWindowFlags kPanel = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                    ImGuiWindowFlags_NoSavedSettings |
                                    ImGuiWindowFlags_NoBringToFrontOnFocus;

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

}  // namespace

void DrawStudio(const StudioSnapshot& snapshot, CommandQueue& commands, StudioTextures& textures) {
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
  const float body = display.y - kStatusHeight - top;

  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(kSidebarWidth, body));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.93f, 0.94f, 0.955f, 1.0f));
  ImGui::Begin("Steps", nullptr, kPanel);
  DrawSidebar(context);
  ImGui::End();
  ImGui::PopStyleColor();

  ImGui::SetNextWindowPos(ImVec2(kSidebarWidth, top));
  ImGui::SetNextWindowSize(ImVec2(display.x - kSidebarWidth, body));
  ImGui::Begin("Screen", nullptr, kPanel);
  if (!snapshot.errors.empty()) {
    for (const std::string& error : snapshot.errors) StatusText(Status::kError, error);
    if (Button("Dismiss")) commands.Push(DismissErrors{});
    ImGui::Separator();
  }
  DrawScreen(context);
  ImGui::End();

  ImGui::SetNextWindowPos(ImVec2(0, top + body));
  ImGui::SetNextWindowSize(ImVec2(display.x, kStatusHeight));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(10, 5));
  ImGui::Begin("Status", nullptr, kPanel);
  ImGui::TextUnformatted(snapshot.status.empty() ? "Ready." : snapshot.status.c_str());
  ImGui::End();
  ImGui::PopStyleVar();
}

}  // namespace recon::ui
