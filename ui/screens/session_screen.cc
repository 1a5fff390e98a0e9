#include <imgui.h>

#include <array>
#include <cstring>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void DrawSessionMenu(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  const bool busy = !s.busy_with.empty();
  const std::string why = "wait for " + s.busy_with + " to finish (or stop it) first";
  if (!BeginMenu("Session")) return;
  // While something runs the session cannot change: the items say so instead of doing nothing.
  if (busy) ImGui::TextDisabled("%s", ("Switching sessions: " + why).c_str());
  if (MenuItem("Open or create...", !busy, why)) context.commands.Push(ShowSessionPicker{true});
  if (!s.recent_sessions.empty()) {
    ImGui::Separator();
    ImGui::TextDisabled("Recent");
    for (const std::string& dir : s.recent_sessions) {
      const bool current = dir == s.session_dir;
      if (MenuItem((dir + "##recent-menu").c_str(), !busy && !current,
                   current ? "this session is open" : why)) {
        context.commands.Push(OpenSession{dir});
      }
    }
  }
  ImGui::Separator();
  // Every change (an episode, a mark, a calibration) is committed to disk when it is made, so
  // there is nothing to save by hand: say so where people look for Save.
  ImGui::TextDisabled("Saved: every change is on disk when it is made");
  ImGui::Separator();
  // Nothing is lost by quitting: what runs stops as when the window is closed, and a take that
  // was not kept is not saved (the same as Discard).
  if (MenuItem(s.busy_with.empty() ? "Quit" : ("Quit (stops " + s.busy_with + ")##quit").c_str())) {
    context.commands.Push(Quit{});
  }
  ImGui::EndMenu();
}

void DrawSessionPicker(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  ScreenHeader("Session", "Open a teaching session, or create one in a new folder.");
  std::array<char, 1024>& folder = context.textures.session_folder;
  ImGui::TextUnformatted("Folder (a new folder creates a tabletop session):");
  const bool entered = InputText("##session-folder", folder.data(), folder.size(), Px(560));
  ImGui::SameLine();
  if (Button("Open or create", folder[0] != '\0', "type the session's folder first") ||
      (entered && folder[0] != '\0')) {
    context.commands.Push(OpenSession{folder.data()});
  }
  if (s.session_open) {
    ImGui::SameLine();
    if (Button("Cancel##session-picker")) context.commands.Push(ShowSessionPicker{false});
  }
  ImGui::Spacing();
  if (s.recent_sessions.empty()) {
    ImGui::TextDisabled("No recent sessions.");
    return;
  }
  ImGui::TextUnformatted("Recent sessions:");
  for (const std::string& dir : s.recent_sessions) {
    if (Selectable((dir + "##recent").c_str(), dir == s.session_dir)) {
      context.commands.Push(OpenSession{dir});
    }
  }
}

}  // namespace recon::ui
