#pragma once

// The Rollouts step's "Check what it looks at" results as a snapshot, for the probe panel's
// tests and the layout tests.

#include <cmath>
#include <string>

#include "tests/ui/studio_test_support.h"

namespace recon::ui::testing {

/// A 10 x 10 heat map that grows away from (x, y) = (0.4, -0.2), blank around (0.56, 0.33).
inline ProbeView::Map Map(const std::string& label, float gain) {
  ProbeView::Map map;
  map.label = label;
  map.nx = map.ny = 10;
  map.bounds = {0.22f, 0.82f, -0.5f, 0.5f};
  for (int iy = 0; iy < 10; ++iy) {
    for (int ix = 0; ix < 10; ++ix) {
      const float x = 0.22f + (ix + 0.5f) * 0.06f, y = -0.5f + (iy + 0.5f) * 0.1f;
      const bool overlaps = std::hypot(x - 0.56f, y - 0.33f) < 0.16f;
      map.values.push_back(overlaps ? NAN : gain * std::hypot(x - 0.4f, y + 0.2f));
    }
  }
  map.scale_max = 0.02f;
  map.markers = {
      {"bowl (home)", {0.4f, -0.2f}}, {"plate", {0.56f, 0.33f}}, {"toast", {0.33f, 0.0f}}};
  return map;
}

inline StudioSnapshot Probed() {
  StudioSnapshot s = SnapshotAt(Progress::kDone, teach::Step::kRollouts);
  for (RolloutView& r : s.rollouts) r.has_replay = false;  // the panel in view, not the playback
  ProbeView& p = s.probe;
  p.present = true;
  p.rows = {{"Baseline", "bowl", 0.00545, 0.128, 0.21, std::nullopt},
            {"Baseline", "plate", 0.00397, 0.0718, 0.13, std::nullopt},
            {"Baseline", "toast", 0.00203, 0.032, std::nullopt, std::nullopt},
            {"RECON (Play)", "bowl", 0.000318, 0.0117, -0.07, std::nullopt},
            {"RECON (Play)", "plate", 0.00216, 0.0987, 1.00, std::nullopt},
            {"RECON (Play)", "toast", 0.000363, 0.00517, std::nullopt, std::nullopt}};
  p.verdicts = {
      "Baseline moves most with the bowl (0.00545 per 10 cm; the plate 0.00397; the "
      "toast 0.00203)",
      "RECON (Play) moves most with the plate (0.00216 per 10 cm; the bowl 0.000318; "
      "the toast 0.000363)"};
  p.note =
      "Each object moved over a 10 x 10 grid in test scene 1038; read-out on 60 other test "
      "scenes.";
  p.objects = {"bowl", "plate", "toast"};
  p.shown_object = "bowl";
  p.maps = {Map("Baseline", 0.04f), Map("RECON (Play)", 0.003f)};
  return s;
}

}  // namespace recon::ui::testing
