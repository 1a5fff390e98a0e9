#include <imgui.h>

#include <algorithm>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

std::string ReadingText(const BeaconView& b) {
  if (b.reading.empty()) return "no reading yet";
  char text[96];
  std::string out;
  for (size_t i = 0; i < b.reading.size(); ++i) {
    std::snprintf(text, sizeof(text), "%s%.3f", i ? ", " : "", b.reading[i]);
    out += text;
  }
  return out + (b.unit.empty() ? "" : " " + b.unit);
}

}  // namespace

void DrawBeaconsScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Beacons", teach::StepPurpose(teach::Step::kBeacons));
  const bool busy = Blocked(s, teach::Step::kBeacons);
  const std::string why = WhyBlocked(s, teach::Step::kBeacons);
  // Which beacon the next click on an object assigns: the first one without an object.
  std::string pending;
  for (const BeaconView& b : s.beacons) {
    if (b.object.empty()) {
      pending = b.name;
      break;
    }
  }
  if (!pending.empty()) {
    ImGui::Text("Click the object beacon '%s' is stuck on, or choose it from the list.",
                pending.c_str());
  }
  context.textures.camera.Update(s.camera, s.camera_frame);
  // The view takes half the room (480 px at most, more in a tall window), the beacons' panel
  // the rest, from 1024 px up.
  const float room = ImGui::GetContentRegionAvail().x;
  const float camera_width = GrowingViewWidth(0.5f, Px(240), Px(480));
  const float panel_width = std::max(Px(200), room - camera_width - Px(16));
  ImGui::BeginGroup();
  const std::optional<std::string> clicked =
      CameraView("camera##beacons", context.textures.camera, camera_width, s.beacons,
                 busy ? std::vector<ObjectView>{} : s.objects);
  ImGui::EndGroup();
  if (clicked && !pending.empty()) context.commands.Push(AssignBeacon{pending, *clicked});
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + panel_width);
  for (const BeaconView& b : s.beacons) {
    ImGui::PushID(b.name.c_str());
    ImGui::Text("Beacon %s (%s)", b.name.c_str(), b.quantity.c_str());
    const std::string preview = b.object.empty() ? "choose an object" : b.object;
    ImGui::SetNextItemWidth(std::min(Px(220), panel_width - Px(60)));
    if (BeginCombo(("marks##object-" + b.name).c_str(), preview.c_str())) {
      for (const ObjectView& o : s.objects) {
        // One label per beacon and object, so a script can choose it: "plate##for-plate".
        if (Selectable((o.name + "##for-" + b.name).c_str(), o.name == b.object) && !busy) {
          context.commands.Push(AssignBeacon{b.name, o.name});
        }
      }
      ImGui::EndCombo();
    }
    StatusText(b.reading.empty() ? Status::kOff : Status::kOk, ReadingText(b));
    // Measured, not configured: the readings' spread over the last 3 s, per axis.
    ImGui::TextWrapped("%.1f Hz, %.0f%% dropped, spread %.1f cm per axis (last 3 s, object still)",
                       b.rate_hz, 100.0 * b.dropout_fraction, 100.0 * b.noise_m);
    ImGui::Separator();
    ImGui::PopID();
  }
  if (s.beacons.empty()) ImGui::TextDisabled("This task uses no beacons.");
  if (busy && !why.empty()) ImGui::TextWrapped("%s", why.c_str());
  ImGui::PopTextWrapPos();
  ImGui::EndGroup();
}

}  // namespace recon::ui
