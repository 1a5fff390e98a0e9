#pragma once

#include <cstddef>
#include <exception>
#include <functional>
#include <vector>

namespace recon {

/// Runs job(i) for every i in [0, count) on up to `threads` threads (the calling one included
/// when there is one thread), each taking the next index as it finishes one. Rethrows the first
/// exception a job threw, after the others have stopped taking new indices.
void ParallelFor(size_t count, unsigned threads, const std::function<void(size_t)>& job);

/// Like ParallelFor, but every job runs to its end whatever the others throw (methods trained or
/// rolled out side by side: one failing must not stop the other). Returns what each job threw,
/// by index (null for those that did not).
std::vector<std::exception_ptr> ParallelForEachCatching(size_t count, unsigned threads,
                                                        const std::function<void(size_t)>& job);

/// Rethrows the first of `errors` that is not null, in index order; nothing when all are.
void RethrowFirst(const std::vector<std::exception_ptr>& errors);

}  // namespace recon
