#include "app/studio/probe_view.h"

#include <algorithm>

#include "app/cli/session_probe.h"
#include "engine/store/probe_summary.h"

namespace recon::studio {

ui::ProbeView BuildProbeView(const store::Session& session, const std::string& shown_object) {
  ui::ProbeView view;
  const std::optional<store::ProbeSummary> summary = store::ReadProbeSummary(session);
  if (!summary) return view;
  view.present = true;
  for (const auto& [method, probed] : summary->methods) {
    for (const auto& [object, o] : probed.objects) {
      view.rows.push_back({probed.label, object, o.action_change_per_10cm,
                           o.feature_change_per_10cm, o.readout_r2});
      if (std::find(view.objects.begin(), view.objects.end(), object) == view.objects.end()) {
        view.objects.push_back(object);
      }
    }
  }
  view.verdicts = cli::ProbeVerdicts(*summary);
  view.out_of_date = cli::ProbeStaleness(session, *summary);
  view.note = cli::ProbeNote(*summary);
  if (view.objects.empty()) return view;
  const bool known =
      std::find(view.objects.begin(), view.objects.end(), shown_object) != view.objects.end();
  view.shown_object = known ? shown_object : view.objects.front();
  for (const auto& [method, probed] : summary->methods) {
    const auto found = probed.objects.find(view.shown_object);
    if (found == probed.objects.end() || found->second.action_change.empty()) continue;
    const report::HeatMap heat = cli::ProbeHeatMap(*summary, method, view.shown_object);
    ui::ProbeView::Map map;
    map.label = probed.label;
    map.nx = heat.nx;
    map.ny = heat.ny;
    map.bounds = {static_cast<float>(heat.x_min), static_cast<float>(heat.x_max),
                  static_cast<float>(heat.y_min), static_cast<float>(heat.y_max)};
    for (double v : heat.values) map.values.push_back(static_cast<float>(v));
    map.scale_max = static_cast<float>(heat.scale_max);
    for (const report::HeatMap::Marker& m : heat.markers) {
      map.markers.push_back({m.label, {static_cast<float>(m.x), static_cast<float>(m.y)}});
    }
    view.maps.push_back(map);
  }
  return view;
}

}  // namespace recon::studio
