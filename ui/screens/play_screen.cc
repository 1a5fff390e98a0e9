#include <imgui.h>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void DrawPlayScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Play data", teach::StepPurpose(teach::Step::kPlay));
  ImGui::TextWrapped(
      "Move the objects around by hand while the camera and the beacons record: these (image, "
      "beacon) pairs teach the features where the objects are, without any demonstration. "
      "Optional; it helps RECON most when demonstrations are few.");
  context.textures.camera.Update(s.camera, s.camera_frame);
  CameraView("camera##play", context.textures.camera, 420.0f, s.beacons, {});
  ImGui::Text("Play samples recorded: %d", s.play_samples);
  const bool blocked = Blocked(s, teach::Step::kPlay);
  if (s.recording_play) {
    StatusText(Status::kBusy, "Recording play data...");
  } else if (Button("Record 30 play samples", !blocked, WhyBlocked(s, teach::Step::kPlay))) {
    context.commands.Push(RecordPlay{30});
  }
}

}  // namespace recon::ui
