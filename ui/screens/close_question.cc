// The question the window's close button raises while something runs: closing stops it, and a
// training stopped that way is lost, so the teacher chooses.

#include <imgui.h>

#include <cctype>
#include <string>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

constexpr char kTitle[] = "Close the studio?";

/// What stopping loses, in the teacher's terms.
std::string WhatIsLost(const StudioSnapshot& s) {
  if (s.training_running) {
    return "The models it trains are lost: the ones saved before it stay, and the session says "
           "its training was cut short when it is opened again.";
  }
  if (s.recording) return "The take is not kept.";
  if (s.rollouts_running) return "A method whose rollouts have not finished writes none.";
  return "What it has not finished is not saved.";
}

}  // namespace

void DrawCloseQuestion(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  if (!s.close_requested && !ImGui::IsPopupOpen(kTitle)) return;
  if (s.close_requested && !ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x / 2, display.y / 2), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(Px(560), 0));
  if (!ImGui::BeginPopupModal(
          kTitle, nullptr,
          ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings)) {
    return;
  }
  if (!s.close_requested) {  // answered, or what ran has ended
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  const std::string busy = s.busy_with.empty() ? "something" : s.busy_with;
  std::string running = busy + " is running.";
  running[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(running[0])));
  ImGui::TextWrapped("%s Closing the studio now stops it. %s", running.c_str(),
                     WhatIsLost(s).c_str());
  ImGui::Spacing();
  if (Button(("Keep " + busy + " running##keep-running").c_str())) {
    context.commands.Push(AnswerClose{false});
  }
  ImGui::SameLine();
  if (Button(("Stop " + busy + " and close##stop-and-close").c_str())) {
    context.commands.Push(AnswerClose{true});
  }
  ImGui::EndPopup();
}

}  // namespace recon::ui
