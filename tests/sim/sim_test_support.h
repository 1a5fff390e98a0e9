#pragma once

#include <memory>

#include "devices/render/mujoco_renderer.h"
#include "devices/sim/simulated_cell.h"

namespace recon::sim::testing {

/// A simulated cell with the real offscreen renderer, 64 x 64 images, installation seed `seed`.
inline std::unique_ptr<SimulatedCell> MakeCell(uint64_t seed = 1) {
  SimulatedCellOptions options;
  options.seed = seed;
  return std::make_unique<SimulatedCell>(options, render::MujocoRendererFactory());
}

}  // namespace recon::sim::testing
