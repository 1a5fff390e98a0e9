#include <imgui.h>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void DrawRolloutsScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Rollouts", teach::StepPurpose(teach::Step::kRollouts));
  if (s.rollouts_running) {
    StatusText(Status::kBusy, "Rolling out...");
  } else if (Button("Run rollouts on 10 new scenes", !Blocked(s, teach::Step::kRollouts),
                    WhyBlocked(s, teach::Step::kRollouts))) {
    context.commands.Push(RunRollouts{10});
  }
  ImGui::Spacing();
  if (ImGui::BeginTable("rollouts", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    ImGui::TableSetupColumn("Policy (beacons removed)");
    ImGui::TableSetupColumn("Metric");
    ImGui::TableSetupColumn("Success");
    ImGui::TableSetupColumn("Scenes");
    ImGui::TableHeadersRow();
    for (const RolloutView& r : s.rollouts) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(r.label.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.3f ± %.3f (%s)", r.metric_mean, r.metric_sem, r.metric_name.c_str());
      ImGui::TableNextColumn();
      if (r.has_success) {
        ImGui::Text("%.0f%%", 100.0 * r.success_rate);
      } else {
        ImGui::TextDisabled("-");
      }
      ImGui::TableNextColumn();
      ImGui::Text("%d", r.tests);
    }
    ImGui::EndTable();
  }
  if (s.rollouts.empty()) ImGui::TextDisabled("No rollouts yet.");
}

}  // namespace recon::ui
