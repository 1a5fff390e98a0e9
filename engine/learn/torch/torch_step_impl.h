#pragma once

// Inside the Torch module: the Torch backend's step (torch_step.cc).

#include <memory>

#include "engine/learn/torch_step.h"

namespace recon::learn {

std::unique_ptr<TorchStep> NewTorchStep(const TorchStepSetup& setup);

}  // namespace recon::learn
