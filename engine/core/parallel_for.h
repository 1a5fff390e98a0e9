#pragma once

#include <cstddef>
#include <functional>

namespace recon {

/// Runs job(i) for every i in [0, count) on up to `threads` threads (the calling one included
/// when there is one thread), each taking the next index as it finishes one. Rethrows the first
/// exception a job threw, after the others have stopped taking new indices.
void ParallelFor(size_t count, unsigned threads, const std::function<void(size_t)>& job);

}  // namespace recon
