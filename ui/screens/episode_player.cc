// The Record step's playback of a recorded demonstration: what the camera saw while the task was
// shown, frame by frame, and (with the saliency on) which pixels a trained policy would act on.

#include <imgui.h>

#include <algorithm>

#include "ui/screens/screens.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

void DrawEpisodePlayer(const ScreenContext& context, float width) {
  const EpisodePlaybackView& p = context.snapshot.episode_playback;
  if (p.episode.empty()) return;
  ImGui::BeginGroup();
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
  const std::string title = Format("%s, what the robot's camera saw: step %d of %d",
                                   p.episode.c_str(), p.frame + 1, p.frames);
  ImGui::TextWrapped("%s", title.c_str());
  // Close beside the title where the width allows, else under it: never past the column.
  const float close_width = ImGui::CalcTextSize("Close").x + 2 * ImGui::GetStyle().FramePadding.x;
  if (ImGui::CalcTextSize(title.c_str()).x + ImGui::GetStyle().ItemSpacing.x + close_width <=
      width) {
    ImGui::SameLine();
  }
  if (Button("Close##episode-playback")) {  // back to the live views
    context.commands.Push(ShowEpisodeFrame{});
  }
  if (p.methods.empty()) {
    ImGui::TextDisabled("Train a policy to see which pixels it acts on here.");
  } else {
    DrawSaliencyToggle(context, true, width);
    if (context.snapshot.saliency != SaliencyMode::kOff && p.methods.size() > 1) {
      ImGui::TextUnformatted("The policy asked:");
      for (const auto& [method, label] : p.methods) {
        ImGui::SameLine();
        if (Button((label + "##episode-saliency").c_str(), method != p.method, "shown now")) {
          context.commands.Push(ShowEpisodeFrame{p.episode, p.frame, method});
        }
      }
    }
  }
  if (p.frames > 0) {
    const float side = std::min(width, Px(320));
    context.textures.episode.Update(p.image, p.image_frame);
    ImGui::Image(context.textures.episode.id(), ImVec2(side, side));
    int frame = p.frame;
    ImGui::SetNextItemWidth(side);
    if (ImGui::SliderInt("##episode-frame", &frame, 0, p.frames - 1) && frame != p.frame) {
      context.commands.Push(ShowEpisodeFrame{p.episode, frame, p.method});
    }
  }
  ImGui::PopTextWrapPos();
  ImGui::EndGroup();
}

}  // namespace recon::ui
