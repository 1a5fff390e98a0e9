#include <imgui.h>

#include <string>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

std::string PlayDataHowTo(const StudioSnapshot& s) {
  // Who moves the objects depends on the cell. The simulated teacher moves the bowl within a
  // scene (Tabletop::SamplePlay), and the chunks follow the takes' scenes (StartSessionPlay),
  // so the plate and its beacon move from one scene to the next.
  std::string who;
  if (s.studio_cell == "real") {
    who = "Move the objects around by hand (the beacon stays on its object)";
  } else if (s.play_scene_samples > 0) {
    who = Format(
        "The simulated teacher moves the bowl around; every %d samples a new scene "
        "puts the plate, and the beacon on it, somewhere else",
        s.play_scene_samples);
  } else {
    who =
        "The simulated teacher moves the bowl around, and each new scene moves the plate with "
        "its beacon";
  }
  return who +
         " while the camera and the beacons record: these (image, beacon) pairs teach the "
         "features where the objects are, without any demonstration. Optional; it helps RECON "
         "most when demonstrations are few.";
}

void DrawPlayScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Play data", teach::StepPurpose(teach::Step::kPlay));
  ImGui::TextWrapped("%s", PlayDataHowTo(s).c_str());
  context.textures.camera.Update(s.camera, s.camera_frame);
  ImGui::BeginGroup();
  CameraView("camera##play", context.textures.camera, GrowingViewWidth(0.5f, Px(300), Px(420)),
             s.beacons, {});
  ImGui::EndGroup();
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::Text("Play samples in the session: %d", s.play_samples);
  const bool blocked = MotionBlocked(s, teach::Step::kPlay);
  if (s.recording_play) {
    StatusText(Status::kBusy,
               Format("Recording play data: %d of %d", s.play_recorded, s.play_target));
    ImGui::ProgressBar(
        s.play_target > 0 ? static_cast<float>(s.play_recorded) / s.play_target : 0.0f,
        ImVec2(Px(300), 0));
    if (Button("Stop")) context.commands.Push(StopPlay{});
  } else if (Button("Record 30 play samples", !blocked, WhyMotionBlocked(s, teach::Step::kPlay))) {
    context.commands.Push(RecordPlay{30});
  }
  // The last sample as the policy's camera saw it, with the beacon's reading: what the feature
  // net learns from.
  if (s.play_image.width > 0) {
    ImGui::Spacing();
    ImGui::TextUnformatted("Last sample (the policy's camera):");
    context.textures.play.Update(s.play_image, s.play_image_frame);
    if (context.textures.play.id() != nullptr) {
      ImGui::Image(context.textures.play.id(), ImVec2(Px(256), Px(256)));
    }
    if (!s.play_reading.empty()) {
      std::string reading;
      for (size_t i = 0; i < s.play_reading.size(); ++i) {
        reading += Format("%s%.3f", i ? ", " : "", s.play_reading[i]);
      }
      ImGui::Text("Beacon: %s m", reading.c_str());
    }
  }
  ImGui::EndGroup();
}

}  // namespace recon::ui
