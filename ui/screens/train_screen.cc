#include <imgui.h>

#include <algorithm>

#include "ui/screens/screens.h"
#include "ui/widgets/loss_plot.h"
#include "ui/widgets/widget_registry.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

/// The loss's unit, for the plots' titles.
const char* LossUnit(const TrainingView& run) {
  return run.loss == "nll" ? "Gaussian NLL, nats" : "squared error, standardised";
}

/// Both methods' curves share one scale per term, so their heights compare.
void DrawRun(const TrainingView& run, float width, const PlotRange& action,
             const PlotRange& beacon) {
  ImGui::BeginGroup();
  ImGui::TextUnformatted(run.label.c_str());
  const float fraction = run.steps > 0 ? static_cast<float>(run.step) / run.steps : 0.0f;
  ImGui::ProgressBar(
      fraction, ImVec2(width, 0),
      run.done ? "done"
               : Format("%d / %d steps, %.0f s", run.step, run.steps, run.seconds).c_str());
  if (!run.action_loss.empty()) {
    LossPlot("action", Format("Action loss (%s): %.3g", LossUnit(run), run.action_loss.back()),
             run.loss_step, run.action_loss, action, width, Px(150));
  }
  if (!run.beacon_loss.empty()) {
    LossPlot("beacon", Format("Beacon loss (%s): %.3g", LossUnit(run), run.beacon_loss.back()),
             run.loss_step, run.beacon_loss, beacon, width, Px(110));
  }
  if (!run.error.empty()) StatusText(Status::kError, run.error);
  if (!run.out_of_date.empty()) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
    StatusText(Status::kWarning, "Out of date: " + run.out_of_date);
    ImGui::PopTextWrapPos();
  }
  ImGui::EndGroup();
}

}  // namespace

void DrawTrainScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Train", teach::StepPurpose(teach::Step::kTrain));
  // The job decides, not the views: a training shows no progress until its data is loaded.
  if (s.training_running) {
    if (Button(s.training_cancelling ? "Cancelling...##cancel-training" : "Cancel training",
               !s.training_cancelling, "the trainers stop at their next step")) {
      context.commands.Push(CancelTraining{});
    }
  } else if (Button("Train Baseline and RECON", !Blocked(s, teach::Step::kTrain),
                    WhyBlocked(s, teach::Step::kTrain))) {
    context.commands.Push(StartTraining{{"baseline", "recon"}});
  }
  for (const std::string* warning : {&s.teacher_mix_warning, &s.slow_takes_warning}) {
    if (warning->empty()) continue;
    ImGui::PushTextWrapPos(ImGui::GetContentRegionAvail().x);
    StatusText(Status::kWarning, *warning);
    ImGui::PopTextWrapPos();
  }
  // A training the studio's closing cut short: the models shown are the older ones.
  if (!s.training_cut_short.empty() && !s.training_running) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::BeginGroup();
    StatusText(Status::kWarning, s.training_cut_short);
    ImGui::EndGroup();
    ImGui::PopTextWrapPos();
    WidgetRegistry::ForThisThread().AddLastRegion("training-cut-short");
  }
  ImGui::Spacing();
  // Side by side, as the paper compares them.
  const float width = (ImGui::GetContentRegionAvail().x - Px(20)) / 2;
  // Every column starts at the same height (SameLine would align the second with the first's
  // last framed widget, a few pixels lower).
  const float top = ImGui::GetCursorPosY();
  PlotRange action, beacon;
  for (const TrainingView& run : s.training) {
    action.Include(run.action_loss);
    beacon.Include(run.beacon_loss);
  }
  for (size_t i = 0; i < s.training.size(); ++i) {
    if (i > 0) {
      ImGui::SameLine();
      ImGui::SetCursorPosY(top);
    }
    DrawRun(s.training[i], width, action, beacon);
  }
  if (s.training.empty()) {
    ImGui::TextDisabled(s.training_running ? "Loading the session's data..."
                                           : "Nothing trained yet.");
  }
}

}  // namespace recon::ui
