#include "engine/core/malloc_tuning.h"

#include <malloc.h>

namespace recon {

void TuneMallocForTraining() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace recon
