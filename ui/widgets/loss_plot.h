#pragma once

#include <string>
#include <vector>

namespace recon::ui {

/// The value range several loss plots share, so curves drawn side by side compare by height.
struct PlotRange {
  float low = 0, high = 0;
  bool any = false;  ///< a finite value was included
  /// Widens the range to hold `values` (ignoring non-finite ones).
  void Include(const std::vector<float>& values);
};

/// A loss curve with axes: the title and its unit above, three labelled ticks on the value axis
/// (`range`'s ends and middle) with grid lines, and the first and last training step under the
/// step axis. `steps[i]` is the step of `values[i]`. Draws a "no data" frame when `values` is
/// empty. Takes `width` x `height` pixels at the cursor.
void LossPlot(const char* id, const std::string& title, const std::vector<float>& steps,
              const std::vector<float>& values, const PlotRange& range, float width, float height);

}  // namespace recon::ui
