// The Torch module's one exported symbol: the table of what it offers (torch_module.h).

#include <ATen/Parallel.h>

#include "engine/learn/torch/archive.h"
#include "engine/learn/torch/torch_step_impl.h"
#include "engine/learn/torch_module.h"

namespace recon::learn {
namespace {

void SetTorchThreads(int threads) { at::set_num_threads(threads); }

const TorchModule kModule = {kTorchModuleInterface, &OpenTorchArchive, &NewTorchArchive,
                             &NewTorchStep, &SetTorchThreads};

}  // namespace
}  // namespace recon::learn

extern "C" __attribute__((visibility("default"))) const recon::learn::TorchModule*
ReconTorchModule() {
  return &recon::learn::kModule;
}
