#include <imgui.h>

#include <algorithm>
#include <vector>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void DrawCalibrateScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  const CalibrationView& c = s.calibration;
  ScreenHeader("Calibrate", teach::StepPurpose(teach::Step::kCalibrate));
  const bool blocked = Blocked(s, teach::Step::kCalibrate);
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
