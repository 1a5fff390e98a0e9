#include <ATen/Parallel.h>

#include "engine/core/error.h"
#include "engine/learn/learner.h"

namespace recon::learn {

void SetThreads(int threads) {
  if (threads < 1) {
    throw UserError("threads must be at least 1 (got " + std::to_string(threads) + ")");
  }
  at::set_num_threads(threads);
}

}  // namespace recon::learn
