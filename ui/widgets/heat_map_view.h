#pragma once

#include "ui/studio/studio_snapshot.h"

namespace recon::ui {

/// A probe's heat map of the table, `width` pixels wide, seen from behind the robot as the
/// report draws it (table x up, table y to the left), each cell in the project's sequential
/// colour scale from 0 to map.scale_max (blank where the object would overlap another), with
/// the objects' places marked. Registered as `id` for the UI driver.
void HeatMapView(const char* id, const ProbeView::Map& map, float width);

}  // namespace recon::ui
