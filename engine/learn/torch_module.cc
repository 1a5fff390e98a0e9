#include "engine/learn/torch_module.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <mutex>

#include "engine/core/error.h"
#include "engine/learn/spatial_softmax.h"

#ifndef RECON_TORCH_MODULE_PATH
#error "RECON_TORCH_MODULE_PATH must name the built Torch module (engine/learn/CMakeLists.txt)"
#endif

namespace recon::learn {

namespace {

using ModuleEntry = const TorchModule* (*)();

std::mutex load_mutex;
std::atomic<const TorchModule*> loaded{nullptr};
// The --threads setting, applied to Torch when (and each time after) the module is loaded.
std::atomic<int> torch_threads{1};

std::string ModulePath() {
  const char* override_path = std::getenv("RECON_TORCH_MODULE");
  return override_path != nullptr && override_path[0] != '\0' ? override_path
                                                              : RECON_TORCH_MODULE_PATH;
}

const TorchModule* Load() {
  const std::string path = ModulePath();
  const std::string why = "checkpoints and the Torch backend need it; ./scripts/build builds it";
  // RTLD_LOCAL: LibTorch's symbols stay the module's. The handle is never closed: Torch
  // registers static state that must outlive every tensor.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* error = dlerror();
    throw UserError("cannot load the Torch module " + path + " (" +
                    (error != nullptr ? error : "unknown error") + "): " + why);
  }
  const auto entry = reinterpret_cast<ModuleEntry>(dlsym(handle, kTorchModuleEntry));
  if (entry == nullptr) {
    throw UserError("the Torch module " + path + " has no " + kTorchModuleEntry + ": " + why);
  }
  const TorchModule* module = entry();
  if (module == nullptr || module->interface_version != kTorchModuleInterface) {
    throw UserError("the Torch module " + path + " was built for another version of recon (" +
                    "interface " +
                    std::to_string(module != nullptr ? module->interface_version : 0) +
                    ", expected " + std::to_string(kTorchModuleInterface) + "): " + why);
  }
  module->set_threads(torch_threads.load());
  return module;
}

}  // namespace

const TorchModule& Torch() {
  if (const TorchModule* module = loaded.load(std::memory_order_acquire)) return *module;
  const std::lock_guard<std::mutex> lock(load_mutex);
  if (loaded.load() == nullptr) loaded.store(Load(), std::memory_order_release);
  return *loaded.load();
}

bool TorchLoaded() { return loaded.load() != nullptr; }

void SetThreads(int threads) {
  if (threads < 1) {
    throw UserError("threads must be at least 1 (got " + std::to_string(threads) + ")");
  }
  torch_threads.store(threads);
  // Loading Torch only to set its thread count would cost every command its start-up time.
  const std::lock_guard<std::mutex> lock(load_mutex);
  if (const TorchModule* module = loaded.load()) module->set_threads(threads);
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
