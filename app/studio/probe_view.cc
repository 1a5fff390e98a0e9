#include "app/studio/probe_view.h"

#include <algorithm>

#include "app/cli/session_probe.h"
#include "engine/store/probe_summary.h"

namespace recon::studio {

namespace {

ui::ProbeView::Map MapOf(const report::HeatMap& heat, const std::string& label) {
  ui::ProbeView::Map map;
  map.label = label;
  map.nx = heat.nx;
  map.ny = heat.ny;
  map.bounds = {static_cast<float>(heat.x_min), static_cast<float>(heat.x_max),
                static_cast<float>(heat.y_min), static_cast<float>(heat.y_max)};
  for (double v : heat.values) map.values.push_back(static_cast<float>(v));
  map.scale_max = static_cast<float>(heat.scale_max);
  for (const report::HeatMap::Marker& m : heat.markers) {
    map.markers.push_back({m.label, {static_cast<float>(m.x), static_cast<float>(m.y)}});
  }
  return map;
}

}  // namespace

ui::ProbeView BuildProbeView(const store::Session& session, const std::string& shown_object) {
  ui::ProbeView view;
  const std::optional<store::ProbeSummary> summary = store::ReadProbeSummary(session);
  if (!summary) return view;
  view.present = true;
  for (const auto& [method, probed] : summary->methods) {
    for (const auto& [object, o] : probed.objects) {
      view.rows.push_back({probed.label, object, o.action_change_per_10cm,
                           o.feature_change_per_10cm, o.readout_r2, o.success_rate});
      if (std::find(view.objects.begin(), view.objects.end(), object) == view.objects.end()) {
        view.objects.push_back(object);
      }
    }
  }
  view.rolled_out = cli::HasOutcomes(*summary);
  view.verdicts = cli::ProbeVerdicts(*summary);
  view.out_of_date = cli::ProbeStaleness(session, *summary);
  view.note = cli::ProbeNote(*summary);
  if (view.objects.empty()) return view;
  const bool known =
      std::find(view.objects.begin(), view.objects.end(), shown_object) != view.objects.end();
  view.shown_object = known ? shown_object : view.objects.front();
  for (const auto& [method, probed] : summary->methods) {
    const auto found = probed.objects.find(view.shown_object);
    if (found == probed.objects.end()) continue;
    if (!found->second.action_change.empty()) {
      view.maps.push_back(
          MapOf(cli::ProbeHeatMap(*summary, method, view.shown_object), probed.label));
    }
    if (!found->second.outcome.empty()) {
      view.outcome_maps.push_back(
          MapOf(cli::ProbeOutcomeMap(*summary, method, view.shown_object), probed.label));
    }
  }
  return view;
}

}  // namespace recon::studio
