#include <imgui.h>

#include <algorithm>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

void DrawRun(const TrainingView& run, float width) {
  ImGui::BeginGroup();
  ImGui::TextUnformatted(run.label.c_str());
  const float fraction = run.steps > 0 ? static_cast<float>(run.step) / run.steps : 0.0f;
  ImGui::ProgressBar(
      fraction, ImVec2(width, 0),
      run.done ? "done"
               : Format("%d / %d steps, %.0f s", run.step, run.steps, run.seconds).c_str());
  if (!run.action_loss.empty()) {
    const auto [low, high] = std::minmax_element(run.action_loss.begin(), run.action_loss.end());
    ImGui::PlotLines("##action", run.action_loss.data(), static_cast<int>(run.action_loss.size()),
                     0, Format("action loss %.3g", run.action_loss.back()).c_str(), *low, *high,
                     ImVec2(width, 140));
  }
  if (!run.beacon_loss.empty()) {
    const auto [low, high] = std::minmax_element(run.beacon_loss.begin(), run.beacon_loss.end());
    ImGui::PlotLines("##beacon", run.beacon_loss.data(), static_cast<int>(run.beacon_loss.size()),
                     0, Format("beacon loss %.3g", run.beacon_loss.back()).c_str(), *low, *high,
                     ImVec2(width, 100));
  }
  if (!run.error.empty()) StatusText(Status::kError, run.error);
  ImGui::EndGroup();
}

}  // namespace

void DrawTrainScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Train", teach::StepPurpose(teach::Step::kTrain));
  const bool running = std::any_of(s.training.begin(), s.training.end(),
                                   [](const TrainingView& t) { return t.running; });
  if (running) {
    if (Button("Cancel training")) context.commands.Push(CancelTraining{});
  } else if (Button("Train Baseline and RECON", !Blocked(s, teach::Step::kTrain),
                    WhyBlocked(s, teach::Step::kTrain))) {
    context.commands.Push(StartTraining{{"baseline", "recon"}});
  }
  ImGui::Spacing();
  // Side by side, as the paper compares them.
  const float width = (ImGui::GetContentRegionAvail().x - 20) / 2;
  for (size_t i = 0; i < s.training.size(); ++i) {
    if (i > 0) ImGui::SameLine();
    DrawRun(s.training[i], width);
  }
  if (s.training.empty()) ImGui::TextDisabled("Nothing trained yet.");
}

}  // namespace recon::ui
