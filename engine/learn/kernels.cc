#include "engine/learn/kernels.h"

#include <atomic>
#include <cstdlib>

#include "engine/core/error.h"
#include "engine/learn/learner.h"

namespace recon::learn::kernels {

namespace generic {
const KernelTable& Table();
}
#if defined(RECON_X86_KERNELS)
namespace avx2 {
const KernelTable& Table();
}
namespace avx512 {
const KernelTable& Table();
}
#endif

namespace {

std::vector<const KernelTable*> Available() {
  std::vector<const KernelTable*> tables = {&generic::Table()};
#if defined(RECON_X86_KERNELS)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    tables.push_back(&avx2::Table());
  }
  if (__builtin_cpu_supports("avx512f")) tables.push_back(&avx512::Table());
#endif
  return tables;
}

const KernelTable* Find(const std::string& name) {
  for (const KernelTable* table : Available()) {
    if (name == table->name) return table;
  }
  return nullptr;
}

const KernelTable* Initial() {
  if (const char* name = std::getenv("RECON_KERNELS"); name != nullptr && *name != '\0') {
    if (const KernelTable* table = Find(name)) return table;
    throw UserError(std::string("RECON_KERNELS=") + name +
                    " is not available on this CPU or build (try generic, avx2 or avx512)");
  }
  return Available().back();
}

std::atomic<const KernelTable*>& Current() {
  static std::atomic<const KernelTable*> current{Initial()};
  return current;
}

}  // namespace

const KernelTable& Kernels() { return *Current().load(std::memory_order_relaxed); }

std::vector<std::string> AvailableKernels() {
  std::vector<std::string> names;
  for (const KernelTable* table : Available()) names.emplace_back(table->name);
  return names;
}

bool UseKernels(const std::string& name) {
  const KernelTable* table = Find(name);
  if (table == nullptr) return false;
  Current().store(table);
  return true;
}

}  // namespace recon::learn::kernels

namespace recon::learn {

std::string KernelsInUse() { return kernels::Kernels().name; }

}  // namespace recon::learn
