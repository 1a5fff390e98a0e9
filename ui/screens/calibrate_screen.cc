#include <imgui.h>

#include <algorithm>
#include <vector>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

/// A real cell's calibration under way: the teacher moves the beacon place by place, and the
/// screen says what to do and shows what the camera and the beacon see.
void DrawGuidedCalibration(const ScreenContext& context, const GuidedCalibrationView& c) {
  const StudioSnapshot& s = context.snapshot;
  const Status status = c.beacon_silent ? Status::kError
                        : c.tag_seen    ? (c.held_fraction > 0 ? Status::kBusy : Status::kWarning)
                                        : Status::kWarning;
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + Px(560));
  StatusText(status, c.prompt);
  ImGui::PopTextWrapPos();
  ImGui::ProgressBar(static_cast<float>(c.points_taken) / std::max(1, c.points_target),
                     ImVec2(Px(360), 0),
                     Format("%d of %d places taken", c.points_taken, c.points_target).c_str());
  ImGui::ProgressBar(c.held_fraction, ImVec2(Px(360), 0), "held still");
  if (Button("Cancel##calibration")) context.commands.Push(CancelCalibration{});
  // The camera with the tag where it is seen and the places taken, numbered.
  std::vector<BeaconView> marks;
  for (size_t i = 0; i < c.taken_pixel.size(); ++i) {
    BeaconView mark;
    mark.name = std::to_string(i + 1);
    mark.label = "place " + mark.name;
    mark.pixel = c.taken_pixel[i];
    marks.push_back(mark);
  }
  if (c.tag_seen) {
    BeaconView tag;
    tag.name = "beacon";
    tag.label = "the beacon's tag";
    tag.pixel = c.tag_pixel;
    marks.push_back(tag);
  }
  context.textures.camera.Update(s.camera, s.camera_frame);
  const float width = GrowingViewWidth(0.6f, Px(240), Px(560));
  CameraView("camera##calibrate", context.textures.camera, width, marks, {});
  if (c.beacon_uwb_m.size() == 3) {
    ImGui::Text("Beacon reads (%.3f, %.3f, %.3f) m in its own frame", c.beacon_uwb_m[0],
                c.beacon_uwb_m[1], c.beacon_uwb_m[2]);
  } else {
    ImGui::TextDisabled("No reading from the beacon yet.");
  }
}

}  // namespace

void DrawCalibrateScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  const CalibrationView& c = s.calibration;
  ScreenHeader("Calibrate", teach::StepPurpose(teach::Step::kCalibrate));
  const bool blocked = Blocked(s, teach::Step::kCalibrate);
  if (c.running && c.guided) {
    DrawGuidedCalibration(context, *c.guided);
    return;
  }
  if (s.studio_cell == "real" && !c.running) {
    ImGui::TextWrapped(
        "You will put the beacon, its tag up, at %d places on the table, one after another: each "
        "is taken when the camera has seen the tag hold still for a second and the beacon has "
        "reported from there.",
        c.points_target);
  }
  if (c.running) {
    ImGui::ProgressBar(static_cast<float>(c.points_collected) / std::max(1, c.points_target),
                       ImVec2(Px(360), 0),
                       Format("%d of %d points", c.points_collected, c.points_target).c_str());
    if (Button("Cancel##calibration")) context.commands.Push(CancelCalibration{});
  } else if (Button(c.present ? "Calibrate again" : "Collect points and fit", !blocked,
                    WhyBlocked(s, teach::Step::kCalibrate))) {
    context.commands.Push(StartCalibration{});
  }
  ImGui::Spacing();
  if (!c.present) {
    ImGui::TextDisabled("Not calibrated yet.");
    return;
  }
  StatusText(
      c.passed ? Status::kOk : Status::kError,
      Format("%s: RMSE %.1f cm, 95th percentile %.1f cm, threshold %.1f cm",
             c.passed ? "PASS" : "FAIL", 100 * c.rmse_m, 100 * c.p95_m, 100 * c.threshold_m));
  // Residual per point, in cm, with the threshold as the plot's top line.
  std::vector<float> cm;
  for (double r : c.residual_m) cm.push_back(static_cast<float>(100.0 * r));
  ImGui::PlotHistogram("##residuals", cm.data(), static_cast<int>(cm.size()), 0,
                       "residual per point (cm)", 0.0f, static_cast<float>(c.threshold_m * 100.0),
                       ImVec2(Px(560), Px(180)));
  int outliers = 0;
  for (bool inlier : c.inlier) outliers += !inlier;
  ImGui::Text("%zu points, %d outliers left out of the fit", c.residual_m.size(), outliers);
}

}  // namespace recon::ui
