#pragma once

#include <string>

namespace recon::ui {

/// A vertical gauge of the grip's height above the table, `height_px` tall: a marker at
/// `height_m`, and the band from `grasp_min_m` to `grasp_max_m` where closing the gripper holds
/// the object (not drawn when both are 0). The scale is a square root from 0 to 30 cm, so the
/// last centimetres, where a grasp is won or lost, take a fifth of the gauge.
void HeightGauge(const char* id, float height_m, float grasp_min_m, float grasp_max_m,
                 float height_px);

/// Where on a gauge of `height_px` a height is drawn, from the top (0) down: the gauge's scale.
float GaugeOffset(float height_m, float height_px);

}  // namespace recon::ui
