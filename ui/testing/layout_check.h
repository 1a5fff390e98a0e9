#pragma once

#include <string>
#include <vector>

#include "ui/widgets/widget_registry.h"

namespace recon::ui {

/// What is wrong with the last frame's layout, one sentence per fault (empty when everything
/// fits): a panel outside the window, a panel whose content runs past its edge with no scrollbar
/// to reach it, a table column too narrow for its header or cells, a registered widget out of
/// its panel's view where no scrollbar brings it in or cut by its column, and two widgets on top
/// of each other (a region, a column or a panel, may hold widgets but not lie partly over one).
/// Call after a frame has been drawn, on the thread that drew it, once the layout has settled
/// (two frames of the same snapshot).
std::vector<std::string> LayoutFaults(const WidgetRegistry& registry);

}  // namespace recon::ui
