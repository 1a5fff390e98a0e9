// The Rollouts step's "Check what it looks at": what each trained method's action moves with, a
// heat map per method of the object shown, and how well the features encode each object.

#include <imgui.h>

#include <algorithm>

#include "ui/screens/screens.h"
#include "ui/widgets/heat_map_view.h"
#include "ui/widgets/widget_registry.h"
#include "ui/widgets/widgets.h"

namespace recon::ui {

namespace {

void DrawOptional(const std::optional<double>& value, const char* format) {
  if (value) {
    ImGui::Text(format, *value);
  } else {
    ImGui::TextDisabled("-");
  }
}

void DrawMaps(const char* id, const std::vector<ProbeView::Map>& maps, const char* what,
              const std::string& object) {
  const float width = std::clamp((ImGui::GetContentRegionAvail().x - Px(16)) / 2, Px(160), Px(420));
  for (size_t i = 0; i < maps.size(); ++i) {
    if (i > 0) ImGui::SameLine(0, Px(16));
    ImGui::BeginGroup();
    ImGui::Text("%s: %s, the %s moved", maps[i].label.c_str(), what, object.c_str());
    HeatMapView(Format("%s##%zu", id, i).c_str(), maps[i], width);
    ImGui::EndGroup();
  }
}

void DrawProbeResults(const ScreenContext& context) {
  const ProbeView& p = context.snapshot.probe;
  if (!p.out_of_date.empty()) StatusText(Status::kWarning, "Out of date: " + p.out_of_date + ".");
  for (const std::string& verdict : p.verdicts) {
    ImGui::Bullet();
    ImGui::TextWrapped("%s", verdict.c_str());
  }
  const int columns = p.rolled_out ? 6 : 5;
  // Sized to its headers and numbers; a window too narrow for them scrolls it sideways (its
  // height fits its rows and the scrollbar).
  const ImGuiStyle& style = ImGui::GetStyle();
  const float height = static_cast<float>(p.rows.size() + 1) *
                           (ImGui::GetTextLineHeight() + 2 * style.CellPadding.y) +
                       style.ScrollbarSize + Px(4);
  if (ImGui::BeginTable("probe", columns,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                            ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX,
                        ImVec2(0, height))) {
    ImGui::TableSetupColumn("Policy");
    ImGui::TableSetupColumn("Object");
    ImGui::TableSetupColumn("Action change / 10 cm");
    ImGui::TableSetupColumn("Feature change / 10 cm");
    ImGui::TableSetupColumn("Read-out R2");
    if (p.rolled_out) ImGui::TableSetupColumn("Rollouts succeeded");
    ImGui::TableHeadersRow();
    for (const ProbeView::Row& row : p.rows) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(row.label.c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(row.object.c_str());
      ImGui::TableNextColumn();
      DrawOptional(row.action_change_per_10cm, "%.3g");
      ImGui::TableNextColumn();
      DrawOptional(row.feature_change_per_10cm, "%.3g");
      ImGui::TableNextColumn();
      if (row.readout_r2) {
        ImGui::Text("%.2f", *row.readout_r2);
      } else {
        ImGui::TextDisabled("- (never moves)");
      }
      if (p.rolled_out) {
        ImGui::TableNextColumn();
        DrawOptional(
            row.success_rate ? std::optional<double>(100 * *row.success_rate) : std::nullopt,
            "%.0f %%");
      }
    }
    ImGui::EndTable();
  }
  WidgetRegistry::ForThisThread().AddLastRegion("probe-results");
  HintText(p.note);
  if (p.maps.empty() && p.outcome_maps.empty()) return;
  ImGui::TextUnformatted("Heat maps, moving:");
  for (const std::string& object : p.objects) {
    ImGui::SameLine();
    if (Button((object + "##probe-object").c_str(), object != p.shown_object, "shown below")) {
      context.commands.Push(ShowProbeObject{object});
    }
  }
  DrawMaps("heat-map", p.maps, "first action", p.shown_object);
  HintText(
      Format("Brighter: the action changes more with the %s there (same scale for every "
             "policy); seen from behind the robot.",
             p.shown_object.c_str()));
  if (p.outcome_maps.empty()) return;
  DrawMaps("outcome-map", p.outcome_maps, "whole rollouts", p.shown_object);
  HintText(
      Format("Bright: the rollout succeeded with the %s there; dark: it failed; blank: not "
             "rolled out (overlap, or out of the arm's reach).",
             p.shown_object.c_str()));
}

}  // namespace

void DrawSaliencyToggle(const ScreenContext& context, bool hint_below, float width) {
  const SaliencyMode shown = context.snapshot.saliency;
  constexpr char kTitle[] = "What drives the action:";
  ImGui::TextUnformatted(kTitle);
  const struct {
    const char* label;
    SaliencyMode mode;
  } choices[] = {{"Off##saliency", SaliencyMode::kOff},
                 {"Gradient##saliency", SaliencyMode::kGradient},
                 {"Occlusion##saliency", SaliencyMode::kOcclusion}};
  const ImGuiStyle& style = ImGui::GetStyle();
  float row = ImGui::CalcTextSize(kTitle).x;
  for (const auto& choice : choices) {
    row += style.ItemSpacing.x + ImGui::CalcTextSize(choice.label, nullptr, true).x +
           2 * style.FramePadding.x;
  }
  // The buttons go under the title where the line is too narrow for both.
  const bool one_line = width <= 0 || row <= width;
  bool first = true;
  for (const auto& choice : choices) {
    if (one_line || !first) ImGui::SameLine();
    first = false;
    if (Button(choice.label, choice.mode != shown, "shown now")) {
      context.commands.Push(SetSaliency{choice.mode});
    }
  }
  if (shown != SaliencyMode::kOff) {
    if (!hint_below) ImGui::SameLine();
    ImGui::TextDisabled(shown == SaliencyMode::kGradient
                            ? "brighter: a pixel's change moves the action more"
                            : "brighter: hiding that part of the view moves the action more");
  }
}

void DrawProbePanel(const ScreenContext& context) {
  const StudioSnapshot& s = context.snapshot;
  const ProbeView& p = s.probe;
  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextUnformatted("What the policies look at");
  if (p.running) {
    if (Button(p.cancelling ? "Cancelling...##cancel-probe" : "Cancel the check", !p.cancelling)) {
      context.commands.Push(CancelProbe{});
    }
    ImGui::SameLine();
    const float fraction = p.total > 0 ? static_cast<float>(p.done) / p.total : 0.0f;
    ImGui::ProgressBar(fraction, ImVec2(-1, 0),
                       p.total > 0 ? Format("%s: %d / %d", p.phase.c_str(), p.done, p.total).c_str()
                                   : "starting...");
  } else {
    const bool trained = std::any_of(s.training.begin(), s.training.end(),
                                     [](const TrainingView& t) { return t.done; });
    const bool simulated = s.cell_kind == "simulated";
    const char* why = !trained               ? "train a policy first"
                      : !s.busy_with.empty() ? "wait for what runs now"
                                             : "";
    const bool can = trained && s.busy_with.empty();
    if (simulated) {
      if (Button("Check what it looks at", can, why)) context.commands.Push(RunProbe{});
      ImGui::SameLine();
      if (Button("...and roll out from every place", can, why)) {
        context.commands.Push(RunProbe{true});
      }
      ImGui::TextWrapped(
          "The check moves each object over the table, everything else held, and measures how "
          "much each policy's first action follows it (seconds). Rolling out from every place "
          "shows where each policy still does the task (minutes).");
    } else {
      if (Button("Read out what its features encode", can, why)) {
        context.commands.Push(RunProbe{});
      }
      ImGui::SameLine();
      ImGui::TextWrapped(
          "fits each beacon's reading from the features on the recorded frames; moving objects "
          "needs the simulated cell, which this real cell's session cannot have");
    }
  }
  // Results that have just arrived are brought into view: they land under the rollouts, below
  // the fold of most windows.
  ImGuiStorage* storage = ImGui::GetStateStorage();
  const ImGuiID seen_id = ImGui::GetID("probe-results-seen");
  const bool arrived = p.present && !p.running && storage->GetInt(seen_id, 1) == 0;
  storage->SetInt(seen_id, p.present && !p.running ? 1 : 0);
  if (arrived) ImGui::SetScrollHereY(0.0f);
  if (p.present) DrawProbeResults(context);
}

}  // namespace recon::ui
