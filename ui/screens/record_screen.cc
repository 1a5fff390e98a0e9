#include <imgui.h>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void DrawRecordScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Record", teach::StepPurpose(teach::Step::kRecord));
  const bool blocked = Blocked(s, teach::Step::kRecord) && !s.recording;
  const std::string why = WhyBlocked(s, teach::Step::kRecord);
  context.textures.camera.Update(s.camera, s.camera_frame);
  ImGui::BeginGroup();
  CameraView("camera##record", context.textures.camera, 420.0f, s.beacons, {});
  ImGui::Text("Teleop: %s", s.teleop.empty() ? "none" : s.teleop.c_str());
  ImGui::Text("Teacher's time so far: %.1f s", s.teacher_seconds);
  ImGui::EndGroup();
  ImGui::SameLine();
  ImGui::BeginGroup();
  if (s.recording) {
    StatusText(Status::kBusy, Format("Recording: %d samples", s.recording_samples));
    if (Button("Stop and keep")) context.commands.Push(StopRecording{});
    ImGui::SameLine();
    if (Button("Discard")) context.commands.Push(DiscardRecording{});
  } else if (Button("Start recording", !blocked, why)) {
    context.commands.Push(StartRecording{});
  }
  if (blocked && !why.empty()) ImGui::TextWrapped("%s", why.c_str());
  ImGui::Spacing();
  ImGui::Text("Demonstrations (%zu)", s.episodes.size());
  if (ImGui::BeginTable("episodes", 5,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                        ImVec2(0, 320))) {
    ImGui::TableSetupColumn("Episode", ImGuiTableColumnFlags_WidthFixed, 120);
    ImGui::TableSetupColumn("Samples", ImGuiTableColumnFlags_WidthFixed, 64);
    ImGui::TableSetupColumn("Time", ImGuiTableColumnFlags_WidthFixed, 60);
    ImGui::TableSetupColumn("Done", ImGuiTableColumnFlags_WidthFixed, 40);
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch);
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
      const bool idle = !s.recording && !blocked;
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
