#include <imgui.h>

#include <algorithm>
#include <vector>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

/// Every method's rollout of the same test scene, side by side, with the controls to step
/// through it or play it at the control rate.
void DrawPlayback(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  std::vector<const RolloutView*> shown;
  for (const RolloutView& r : s.rollouts) {
    if (r.has_replay) shown.push_back(&r);
  }
  if (shown.empty()) return;
  const RolloutView& first = *shown.front();
  const int scenario = first.scenario, frame = first.frame;
  int frames = 0;
  for (const RolloutView* r : shown) frames = std::max(frames, r->frames);
  const bool idle = !s.rollouts_running;
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::Text("Playback: test scene %d of %d (seed %llu), beacons removed", scenario + 1,
              first.tests, static_cast<unsigned long long>(first.scenario_seed));
  if (Button("< Scene", idle && scenario > 0)) {
    context.commands.Push(ShowRolloutFrame{scenario - 1, 0});
  }
  ImGui::SameLine();
  if (Button("Scene >", idle && scenario + 1 < first.tests)) {
    context.commands.Push(ShowRolloutFrame{scenario + 1, 0});
  }
  ImGui::SameLine(0, Px(24));
  if (Button("|<", idle)) context.commands.Push(ShowRolloutFrame{scenario, 0});
  ImGui::SameLine();
  if (Button("<##step-back", idle && frame > 0)) {
    context.commands.Push(ShowRolloutFrame{scenario, frame - 1});
  }
  ImGui::SameLine();
  if (s.rollouts_playing) {
    if (Button("Pause")) context.commands.Push(PlayRollouts{false});
  } else if (Button("Play", idle)) {
    context.commands.Push(PlayRollouts{true});
  }
  ImGui::SameLine();
  if (Button(">##step", idle && frame + 1 < frames)) {
    context.commands.Push(ShowRolloutFrame{scenario, frame + 1});
  }
  ImGui::SameLine();
  if (Button(">|", idle)) context.commands.Push(ShowRolloutFrame{scenario, frames - 1});
  ImGui::SameLine(0, Px(24));
  int slider = frame;
  const float step_text = ImGui::CalcTextSize("step 0000, 000.0 s").x;
  ImGui::SetNextItemWidth(
      std::clamp(ImGui::GetContentRegionAvail().x - step_text - Px(16), Px(100), Px(300)));
  // The step is written beside the slider, never under its handle.
  if (ImGui::SliderInt("##frame", &slider, 0, std::max(0, frames - 1), "") && idle) {
    context.commands.Push(ShowRolloutFrame{scenario, slider});
  }
  ImGui::SameLine();
  ImGui::Text("step %d, %.1f s", frame, 0.1 * frame);
  DrawSaliencyToggle(context);

  ImageTexture* textures[2] = {&context.textures.rollout, &context.textures.rollout_other};
  // Two frames side by side that fit the screen from 1024 x 640 up: at most 480 px wide, and as
  // high as the space under the controls allows (the frames are 4:3), with a line for the outcome.
  const ImVec2 room = ImGui::GetContentRegionAvail();
  const float line = ImGui::GetTextLineHeightWithSpacing();
  const float width = std::max(
      Px(80), std::min({Px(480), (room.x - Px(16)) / 2, (room.y - 2.5f * line) * 4.0f / 3.0f}));
  for (size_t i = 0; i < shown.size() && i < 2; ++i) {
    const RolloutView& r = *shown[i];
    if (i > 0) ImGui::SameLine(0, Px(16));
    ImGui::BeginGroup();
    textures[i]->Update(r.frame_image, r.frame_id);
    if (textures[i]->id() != nullptr && textures[i]->width() > 0) {
      ImGui::Image(textures[i]->id(),
                   ImVec2(width, width * textures[i]->height() / textures[i]->width()));
    }
    // Wrapped to the frame's width, so a long outcome never pushes the other panel away.
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
    // The outcome first, the number on a line of its own (a wrapped line never splits it).
    StatusText(r.has_success ? (r.scenario_succeeded ? Status::kOk : Status::kError) : Status::kOff,
               r.label + (r.has_success ? (r.scenario_succeeded ? ": success" : ": failed") : ""));
    ImGui::TextDisabled("%s: %.3f", r.metric_name.c_str(), r.scenario_metric);
    ImGui::PopTextWrapPos();
    // What went wrong, as the summary's details tell it (the same words as the report's).
    const size_t scene = static_cast<size_t>(r.scenario);
    if (!r.scenario_succeeded && scene < r.scene_failures.size() &&
        !r.scene_failures[scene].empty()) {
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
      ImGui::TextDisabled("%s", r.scene_failures[scene].c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::EndGroup();
  }
}

}  // namespace

void DrawRolloutsScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Rollouts", teach::StepPurpose(teach::Step::kRollouts));
  // On a real cell the policies run trials on the arm; a session taught in the simulated cell
  // keeps its simulated rollouts too, on the same test scenes, labelled apart.
  if (s.studio_cell == "real") DrawTrialsPanel(context);
  if (s.cell_kind == "real") {  // no simulation of a real cell's scene to roll out in
    DrawProbePanel(context);
    return;
  }
  if (s.studio_cell == "real") {
    ImGui::Spacing();
    ImGui::Separator();
    ImGui::TextUnformatted(
        "Simulated rollouts (the session's simulated cell, the same test scenes)");
  }
  if (s.rollouts_running) {
    if (Button(s.rollouts_cancelling ? "Cancelling...##cancel-rollouts" : "Cancel rollouts",
               !s.rollouts_cancelling, "the rollouts stop at their next step")) {
      context.commands.Push(CancelRollouts{});
    }
    ImGui::SameLine();
    const float fraction = s.rollout_steps_total > 0 ? static_cast<float>(s.rollout_steps_done) /
                                                           static_cast<float>(s.rollout_steps_total)
                                                     : 0.0f;
    ImGui::ProgressBar(fraction, ImVec2(-1, 0),
                       s.rollout_steps_total > 0
                           ? Format("rolling out on %d scenes: %d / %d steps", s.rollout_tests,
                                    s.rollout_steps_done, s.rollout_steps_total)
                                 .c_str()
                           : "starting the rollouts...");
  } else {
    if (Button("Run rollouts", !MotionBlocked(s, teach::Step::kRollouts),
               WhyMotionBlocked(s, teach::Step::kRollouts))) {
      context.commands.Push(RunRollouts{s.rollout_tests});
    }
    ImGui::SameLine();
    ImGui::Text("on %d new scenes, beacons removed, every trained method on the same ones",
                s.rollout_tests);
  }
  // How long each rollout runs, and why: a slow teacher's policy is given a teacher's time.
  if (s.rollout_limit_s > 0) {
    if (!s.rollout_limit_note.empty()) {
      StatusText(Status::kWarning, "Each rollout runs " + Format("%.0f s: ", s.rollout_limit_s) +
                                       s.rollout_limit_note);
    } else {
      ImGui::TextDisabled(
          "Each rollout runs %.0f s (1.5 times the longest kept take, %.1f s, "
          "and at least the task's own limit)",
          s.rollout_limit_s, s.longest_take_s);
    }
  }
  ImGui::Spacing();
  // Sized to the headers: the metric's name is long, and a header cut short names nothing.
  if (ImGui::BeginTable(
          "rollouts", 4,
          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("Policy (beacons removed)");
    const std::string metric = s.rollouts.empty() ? "Metric" : s.rollouts[0].metric_name;
    ImGui::TableSetupColumn(metric.c_str());
    ImGui::TableSetupColumn("Success");
    ImGui::TableSetupColumn("Scenes");
    ImGui::TableHeadersRow();
    for (const RolloutView& r : s.rollouts) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(r.label.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.3f ± %.3f", r.metric_mean, r.metric_sem);
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
  for (const RolloutView& r : s.rollouts) {
    if (!r.out_of_date.empty()) {
      StatusText(Status::kWarning,
                 Format("Out of date: %s: %s.", r.label.c_str(), r.out_of_date.c_str()));
    }
  }
  DrawPlayback(context);
  DrawProbePanel(context);
}

}  // namespace recon::ui
