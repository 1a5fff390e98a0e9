#include "engine/learn/torch_module.h"

#include <atomic>

#include "engine/core/error.h"
#include "engine/core/loadable_module.h"
#include "engine/learn/spatial_softmax.h"

#ifndef RECON_TORCH_MODULE_PATH
#error "RECON_TORCH_MODULE_PATH must name the built Torch module (engine/learn/CMakeLists.txt)"
#endif

namespace recon::learn {

namespace {

// The --threads setting, applied to Torch when (and each time after) the module is loaded.
std::atomic<int> torch_threads{1};

const TorchModule* Load() {
  const LoadableModule module = {ModulePath("RECON_TORCH_MODULE", RECON_TORCH_MODULE_PATH),
                                 kTorchModuleEntry, "the Torch module",
                                 "checkpoints and the Torch backend need it"};
  const auto* table =
      static_cast<const TorchModule*>(LoadModuleTable(module, kTorchModuleInterface));
  table->set_threads(torch_threads.load());
  return table;
}

LazyModuleTable<TorchModule> torch_module(&Load);

}  // namespace

const TorchModule& Torch() { return torch_module.Get(); }

void SetThreads(int threads) {
  if (threads < 1) {
    throw UserError("threads must be at least 1 (got " + std::to_string(threads) + ")");
  }
  torch_threads.store(threads);
  // Loading Torch only to set its thread count would cost every command its start-up time.
  torch_module.IfLoaded([threads](const TorchModule& module) { module.set_threads(threads); });
}

std::unique_ptr<TorchStep> MakeTorchStep(const Architecture& arch, const TrainConfig& train) {
  TorchStepSetup setup;
  setup.arch = arch;
  setup.train = train;
  setup.y_size = arch.spec.YSize();
  setup.policy_min_logvar = train.PolicyMinLogVar(arch.spec.u_dim, arch.network.action_chunk);
  setup.beacon_min_logvar.assign(static_cast<size_t>(arch.spec.b_dim), train.NllMinLogVar());
  if (arch.spatial_softmax) {
    setup.keypoint_x = KeypointCoordinates(arch.keypoints.w);
    setup.keypoint_y = KeypointCoordinates(arch.keypoints.h);
  }
  return Torch().new_step(setup);
}

}  // namespace recon::learn
