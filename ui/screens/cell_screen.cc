#include <imgui.h>

#include <cstdio>

#include "ui/screens/screens.h"
#include "ui/widgets/camera_view.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

/// What is plugged into this computer, whether or not the session uses it.
void DrawConnectedDevices(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ImGui::AlignTextToFramePadding();
  ImGui::Text("Plugged in (%s):", s.connected_where.c_str());
  ImGui::SameLine();
  if (Button("Rescan")) context.commands.Push(RescanDevices{});
  if (!s.connected_scanned) {
    ImGui::TextDisabled("Looking...");
    return;
  }
  if (s.connected.empty()) {
    ImGui::TextDisabled("No UWB beacons, cameras, gamepads or robots found.");
    return;
  }
  // Sized to their content (a device's name is long); the detail takes what is left and wraps.
  if (!ImGui::BeginTable(
          "connected", 4,
          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    return;
  }
  ImGui::TableSetupColumn("Kind");
  ImGui::TableSetupColumn("Path");
  ImGui::TableSetupColumn("Name");
  ImGui::TableSetupColumn("Detail", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableHeadersRow();
  for (const ConnectedDeviceView& d : s.connected) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    StatusText(d.usable ? Status::kOk : Status::kError, d.kind);
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(d.path.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(d.identity.empty() ? "-" : d.identity.c_str());
    ImGui::TableNextColumn();
    ImGui::TextWrapped("%s", d.detail.c_str());
  }
  ImGui::EndTable();
}

}  // namespace

void DrawCellScreen(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Cell", teach::StepPurpose(teach::Step::kCell));
  ImGui::Text("Cell: %s%s", s.studio_cell.c_str(),
              s.world.empty() ? "" : (", task " + s.world).c_str());
  if (s.session_open && s.cell_kind != s.studio_cell) {
    StatusText(Status::kWarning,
               Format("This session was taught in the %s cell: here its trained policies run "
                      "trials on the arm (Rollouts); nothing is recorded or calibrated.",
                      s.cell_kind.c_str()));
  }
  ImGui::Spacing();
  if (ImGui::BeginTable(
          "devices", 5,
          ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("Device");
    ImGui::TableSetupColumn("Kind");
    ImGui::TableSetupColumn("Status");
    ImGui::TableSetupColumn("Rate");
    ImGui::TableSetupColumn("Detail", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableHeadersRow();
    for (const DeviceView& d : s.devices) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(d.role.c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(d.kind.c_str());
      ImGui::TableNextColumn();
      if (!d.last_error.empty()) {
        StatusText(Status::kError, "error");
      } else {
        StatusText(d.connected ? Status::kOk : Status::kOff,
                   d.connected ? "connected" : "not connected");
      }
      ImGui::TableNextColumn();
      if (d.rate_hz > 0) {
        ImGui::Text("%.1f Hz", d.rate_hz);
      } else {
        ImGui::TextDisabled("-");
      }
      ImGui::TableNextColumn();
      ImGui::TextWrapped("%s", d.last_error.empty() ? d.detail.c_str() : d.last_error.c_str());
    }
    ImGui::EndTable();
  }
  if (s.devices.empty()) ImGui::TextDisabled("No devices: open or create a session first.");
  if (!s.safety.limits.empty()) {
    ImGui::TextWrapped(
        "Safety envelope on every arm command: %s. Limited so far: %lld of %lld commands.",
        s.safety.limits.c_str(), static_cast<long long>(s.safety.changed),
        static_cast<long long>(s.safety.commands));
  }
  ImGui::Spacing();
  DrawConnectedDevices(context);
  ImGui::Spacing();
  context.textures.camera.Update(s.camera, s.camera_frame);
  CameraView("camera##cell", context.textures.camera, GrowingViewWidth(0.5f, Px(240), Px(480)),
             s.beacons, {});
}

}  // namespace recon::ui
