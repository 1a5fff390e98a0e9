#include <imgui.h>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void DrawReportScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Report", teach::StepPurpose(teach::Step::kReport));
  ImGui::TextWrapped(
      "The report is one self-contained HTML file with the session's losses, beacon traces, "
      "calibration residuals, rollouts and teaching time, and every figure as a PNG.");
  if (Button("Write the report", !Blocked(s, teach::Step::kReport),
             WhyBlocked(s, teach::Step::kReport))) {
    context.commands.Push(WriteReport{});
  }
  if (!s.report_path.empty()) {
    StatusText(Status::kOk, "Written: " + s.report_path);
    if (Button("Open in browser")) context.commands.Push(OpenReport{});
  }
}

}  // namespace recon::ui
