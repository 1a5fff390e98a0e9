// The Rollouts step's trials on a real arm: the protocol a lab runs a trained policy by, and the
// trials judged so far with their frames to play back.

#include <imgui.h>

#include <algorithm>
#include <vector>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

/// What the teacher may say of a trial that did not succeed (the tabletop's failures).
constexpr const char* kFailureReasons[] = {"missed the toast", "took it to the bowl",
                                           "dropped it on the way", "other"};

/// The live camera with the objects' places for the trial drawn over it.
void DrawLayoutCamera(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  std::vector<BeaconView> marks;
  for (const TrialView::Object& o : s.trial.layout) {
    BeaconView mark;
    mark.name = o.name;
    mark.label = o.name + " here";
    mark.pixel = o.pixel;
    marks.push_back(mark);
  }
  context.textures.camera.Update(s.camera, s.camera_frame);
  const float width = std::clamp(ImGui::GetContentRegionAvail().x * 0.5f, Px(240), Px(480));
  CameraView("camera##trial", context.textures.camera, width, marks, {});
}

void DrawTrialUnderWay(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  const TrialView& t = s.trial;
  ImGui::Text("%s: trial %d (%d of %d in this run), test scene seed %llu", t.label.c_str(),
              t.number, t.number - t.first + 1, t.last - t.first + 1,
              static_cast<unsigned long long>(t.scene_seed));
  if (!t.message.empty()) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + Px(640));
    StatusText(Status::kError, t.message);
    ImGui::PopTextWrapPos();
  }
  switch (t.phase) {
    case TrialPhase::kSetUp:
      ImGui::TextUnformatted("Set the table up like this (table frame, metres), then run it:");
      for (const TrialView::Object& o : t.layout) {
        ImGui::BulletText("%s at x %.2f, y %.2f", o.name.c_str(), o.table_m[0], o.table_m[1]);
      }
      if (Button(Format("Ready: run trial %d", t.number).c_str(), !s.safety.estop,
                 "release the e-stop first")) {
        context.commands.Push(RunTrial{});
      }
      ImGui::SameLine();
      if (Button("End trials")) context.commands.Push(EndTrials{});
      break;
    case TrialPhase::kCountdown:
    case TrialPhase::kHoming:
    case TrialPhase::kRunning:
      if (t.phase == TrialPhase::kCountdown) {
        StatusText(Status::kWarning,
                   Format("The arm moves in %.1f s: it returns home, then the policy runs",
                          t.countdown_s));
      } else if (t.phase == TrialPhase::kHoming) {
        StatusText(Status::kWarning, "The arm returns to its home pose");
        ImGui::ProgressBar(t.homing_progress, ImVec2(Px(360), 0),
                           Format("%.0f%% of the way home", 100.0 * t.homing_progress).c_str());
      } else {
        ImGui::ProgressBar(static_cast<float>(t.step) / std::max(1, t.max_steps),
                           ImVec2(Px(360), 0),
                           Format("step %d of %d", t.step, t.max_steps).c_str());
      }
      if (Button("STOP the trial", true, "", Px(240))) context.commands.Push(StopTrial{});
      break;
    case TrialPhase::kJudge:
      ImGui::Text("%s after %d steps. Did it put the toast on the plate?",
                  t.stopped ? "You stopped it" : "Its time is up", t.step);
      if (Button("Success")) context.commands.Push(JudgeTrial{true, ""});
      for (const char* reason : kFailureReasons) {
        ImGui::SameLine();
        if (Button(Format("Failure: %s", reason).c_str())) {
          context.commands.Push(JudgeTrial{false, reason});
        }
      }
      break;
    case TrialPhase::kNone:
      break;
  }
  DrawLayoutCamera(context);
}

void DrawJudgedTrials(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  for (const RealTrialsView& r : s.real_trials) {
    ImGui::Text("%s: %d of %zu trials succeeded", r.label.c_str(), r.successes, r.trials.size());
    if (!r.out_of_date.empty()) {
      StatusText(Status::kWarning, Format("Out of date: %s.", r.out_of_date.c_str()));
    }
    for (const RealTrialsView::Row& row : r.trials) {
      if (Button(Format("Play##%s%d", r.method.c_str(), row.number).c_str(), row.has_frames,
                 "this trial kept no frames")) {
        context.commands.Push(ShowTrialFrame{r.method, row.number, 0});
      }
      ImGui::SameLine();
      ImGui::Text("trial %d: %s%s%s%s", row.number, row.succeeded ? "success" : "failure",
                  row.reason.empty() ? "" : ": ", row.reason.c_str(),
                  row.stopped ? " (stopped)" : "");
    }
  }
  const TrialPlaybackView& p = s.trial_playback;
  if (p.number == 0 || p.frames == 0) return;
  ImGui::Separator();
  ImGui::Text("Trial %d of %s, what the policy saw: step %d of %d", p.number, p.method.c_str(),
              p.frame + 1, p.frames);
  DrawSaliencyToggle(context);
  context.textures.rollout.Update(p.image, p.image_frame);
  ImGui::Image(context.textures.rollout.id(), ImVec2(Px(192), Px(192)));
  int frame = p.frame;
  ImGui::SetNextItemWidth(Px(360));
  if (ImGui::SliderInt("##trial-frame", &frame, 0, p.frames - 1) && frame != p.frame) {
    context.commands.Push(ShowTrialFrame{p.method, p.number, frame});
  }
}

}  // namespace

void DrawTrialsPanel(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ImGui::Separator();
  ImGui::TextUnformatted("Trials on the real arm");
  if (s.trial.phase != TrialPhase::kNone) {
    DrawTrialUnderWay(context);
    return;
  }
  ImGui::TextWrapped(
      "A lab's protocol: the screen shows each test layout, you set it up and run the trial, the "
      "policy drives the arm through the safety envelope, and you judge it. Every judged trial "
      "is kept.");
  const bool blocked = MotionBlocked(s, teach::Step::kRollouts);
  for (const TrainingView& t : s.training) {
    if (!t.done) continue;
    if (Button(Format("Run %d trials of %s", s.rollout_tests, t.label.c_str()).c_str(), !blocked,
               WhyMotionBlocked(s, teach::Step::kRollouts))) {
      context.commands.Push(StartTrials{t.method, s.rollout_tests});
    }
    ImGui::SameLine();
  }
  ImGui::NewLine();
  DrawJudgedTrials(context);
}

}  // namespace recon::ui
