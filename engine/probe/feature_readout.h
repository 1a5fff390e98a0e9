#pragma once

// What a method's features encode of each object: test scenes of the simulated cell rendered at
// their start, and a linear read-out of every object's table position from phi, scored on the
// scenes it was not fitted on.

#include <atomic>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/probe/distractor_probe.h"
#include "engine/probe/linear_readout.h"
#include "engine/worlds/world.h"

namespace recon::probe {

/// The first observation of each scene and where each object stood in it.
struct SceneFrames {
  ProbeSubject::Rows xs, ys;
  std::map<std::string, std::vector<std::vector<double>>> positions;  ///< object -> [x, y] rows
};

/// Resets `world` to each seed and keeps what it shows. ProbeCancelled when `cancel` is raised.
SceneFrames RenderScenes(worlds::World& world, const std::vector<uint64_t>& seeds,
                         const ProbeProgress& progress = nullptr,
                         const std::atomic<bool>* cancel = nullptr);

/// Per object, the read-out of its position from `subject`'s features (FitLinearReadout, one
/// scene in four held out); none for an object that stands in the same place (within 1 mm) in
/// every scene, which leaves nothing to read out.
std::map<std::string, std::optional<ReadoutScore>> ReadOutObjects(const ProbeSubject& subject,
                                                                  const SceneFrames& frames);

}  // namespace recon::probe
